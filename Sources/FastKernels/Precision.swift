/// The precision the fast engine computes in (`FastOptions`).
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

extension Precision {
  /// The smallest positive normal magnitude of the precision: what the
  /// squares of a test must stay above (`LengthScale.problem`).
  package var smallestNormal: Double {
    switch self {
    case .float: Double(Float.leastNormalMagnitude)
    case .double: Double.leastNormalMagnitude
    }
  }
}
