import RealModule

/// A floating-point type the renderer computes in.
///
/// Renders run in `Float` or `Double`; the reference that errors are
/// measured against is `Float80` where the platform has it (x86) and
/// `DoubleDouble` elsewhere (Apple Silicon), both more precise than Double.
/// The choice is made inside this module (see `Precision`), so every generic
/// function here is specialised for the concrete type rather than dispatched
/// through witness tables.
public protocol RayScalar: Real, BinaryFloatingPoint, Sendable {}

extension Float: RayScalar {}
extension Double: RayScalar {}
#if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
  extension Float80: RayScalar {}

  /// The reference precision: Float80 (64-bit significand, IEEE) where the
  /// platform has it. `DoubleDouble` is tested against it here.
  public typealias ReferenceScalar = Float80
#else
  /// The reference precision: a double-double (106-bit significand, see
  /// `DoubleDouble` for its bounds) where there is no Float80.
  public typealias ReferenceScalar = DoubleDouble
#endif
extension DoubleDouble: RayScalar {}

/// The precision a render computes in, as chosen on the command line.
public enum Precision: String, CaseIterable, Sendable {
  case float
  case double
}

extension RayScalar {
  /// Converts exactly when `self` is representable, otherwise rounds to
  /// nearest; used where Double scene values enter a render precision.
  @inlinable
  static func from(_ value: Double) -> Self { Self(value) }
}
