import Geometry

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

/// The precision the fast engine computes in, as chosen on the command
/// line; the readers check that the scene's numbers fit it
/// (`PrecisionRange`).
@usableFromInline
package enum Precision: String, CaseIterable, Sendable {
  case float
  case double
}

/// How the fast engine solves the sphere's quadratic.
@usableFromInline
package enum IntersectionMethod: String, CaseIterable, Sendable {
  /// The course's formulas in working precision: b² − 4ac and
  /// (−b ± √Δ)/2a for spheres, (d − n·o)/(n·d) for planes.
  case naive
  /// Cancellation-free, relative to the ray's origin: see
  /// `SphereIntersection.stableRoot` and `PlaneIntersection.stableT`.
  case stable
}
