/// Anything a ray can hit: the one hit protocol of the model (the course's
/// `Hitable`).
///
/// The public model (Sphere, Plane, Group) conforms to it. Renders do not call
/// it per ray: `CompiledScene` flattens a model into concrete arrays that the
/// loop walks without dynamic dispatch, using the same intersection routines.
public protocol Intersectable<Scalar> {
  associatedtype Scalar: RayScalar

  /// The nearest hit with tMin < t < tMax, or nil.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Hit<Scalar>?

  /// Whether any hit lies in tMin < t < tMax: the cheaper question a shadow
  /// ray asks, which needs no normal and may stop at the first hit.
  func occludes(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Bool
}

extension Intersectable {
  public func occludes(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Bool {
    intersect(ray, after: tMin, before: tMax) != nil
  }
}

/// How the sphere's quadratic is solved.
public enum IntersectionMethod: String, CaseIterable, Sendable {
  /// The course's formula: b² − 4ac and (−b ± √Δ)/2a in working precision.
  case naive
  /// Cancellation-free: see `SphereIntersection.stableRoot`.
  case stable
}
