#if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
  /// The reference precision: Float80 (64-bit significand, IEEE) where the
  /// platform has it. `DoubleDouble` is tested against it here.
  @usableFromInline
  package typealias ReferenceScalar = Float80
#else
  /// The reference precision: a double-double (106-bit significand, see
  /// `DoubleDouble` for its bounds) where there is no Float80.
  @usableFromInline
  package typealias ReferenceScalar = DoubleDouble
#endif
