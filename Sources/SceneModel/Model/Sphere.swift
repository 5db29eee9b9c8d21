/// A sphere: all points at distance `radius` from `center`.
public struct Sphere<Scalar: RayScalar>: Hashable, Sendable {
  public var center: Vector3<Scalar>
  public var radius: Scalar
  public var materialIndex: Int

  public init(center: Vector3<Scalar>, radius: Scalar, materialIndex: Int = 0) {
    self.center = center
    self.radius = radius
    self.materialIndex = materialIndex
  }
}

extension Sphere: Intersectable {
  /// The nearest hit in (tMin, tMax) by the given method.
  ///
  /// Misses return nil; a tangent ray hits at its double root; a ray from
  /// inside (or from the surface, with tMin = 0) hits the far side. The
  /// normal is outward and unit length. The stable method's relative error
  /// of t is a few ulps away from the silhouette, whatever the ratio of
  /// distance to radius (see the stiff suite).
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    switch method {
    case .naive:
      guard
        let t = SphereIntersection.naiveRoot(
          origin: ray.origin, direction: ray.direction, center: center,
          radius: radius, after: tMin, before: tMax)
      else { return nil }
      let normal = SphereIntersection.naiveNormal(
        origin: ray.origin, direction: ray.direction, center: center, t: t)
      return Hit(t: t, normal: normal, materialIndex: materialIndex)
    case .stable:
      // The sphere as seen from the ray's origin: p = centre − o and
      // c = |p|² − r², each rounded once.
      let relative = CameraRelative.sphere(
        center: center, radius: radius, eye: ray.origin, as: Scalar.self)
      let a = ray.direction.lengthSquared
      let inverseA = SphereIntersection.inverseLengthSquared(a)
      let radiusSquared = radius * radius
      guard
        let root = SphereIntersection.stableRoot(
          direction: ray.direction, lengthSquared: a,
          inverseLengthSquared: inverseA, offset: relative.offset,
          c: relative.c, radiusSquared: radiusSquared,
          after: tMin, before: tMax)
      else { return nil }
      let normal = SphereIntersection.stableNormal(
        direction: ray.direction, lengthSquared: a,
        inverseLengthSquared: inverseA, t: root.t,
        offset: relative.offset, c: relative.c, radiusSquared: radiusSquared,
        inverseRadius: 1 / radius, entering: root.entering)
      return Hit(t: root.t, normal: normal, materialIndex: materialIndex)
    }
  }
}
