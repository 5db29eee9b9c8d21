/// Anything a ray can hit: the one hit protocol of the model (the course's
/// `Hitable`).
///
/// Sphere, Plane, Triangle, TriangleMesh, Group and Transform conform to
/// it, and the course engine (`CourseEngine`) renders by calling it for
/// every object of the scene's group. The fast engine computes the same
/// numbers from the same functions (`SphereIntersection`,
/// `PlaneIntersection`, `TriangleIntersection`), on records prepared once
/// per render.
public protocol Intersectable<Scalar> {
  associatedtype Scalar: RayScalar

  /// The nearest hit with tMin < t < tMax by `method`, or nil. A tie
  /// (two surfaces at the same t) goes to the one tested first.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>?

  /// Whether any hit lies in tMin < t < tMax: the cheaper question a shadow
  /// ray asks, which needs no normal and may stop at the first hit.
  func occludes(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Bool
}

extension Intersectable {
  /// The nearest hit with tMin < t < tMax by the stable method, or nil.
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Hit<Scalar>? {
    intersect(ray, after: tMin, before: tMax, method: .stable)
  }

  public func occludes(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Bool {
    intersect(ray, after: tMin, before: tMax) != nil
  }
}

/// How the sphere's quadratic is solved.
public enum IntersectionMethod: String, CaseIterable, Sendable {
  /// The course's formulas in working precision: b² − 4ac and
  /// (−b ± √Δ)/2a for spheres, (d − n·o)/(n·d) for planes.
  case naive
  /// Cancellation-free, relative to the ray's origin: see
  /// `SphereIntersection.stableRoot` and `PlaneIntersection.stableT`.
  case stable
}
