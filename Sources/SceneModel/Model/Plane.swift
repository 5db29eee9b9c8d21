/// The infinite plane n·P = offset, with n of unit length.
public struct Plane<Scalar: RayScalar>: Hashable, Sendable {
  /// Unit normal; hits report it as given, whichever side the ray comes from.
  public var normal: Vector3<Scalar>
  public var offset: Scalar
  public var materialIndex: Int

  /// A plane n·P = d; a normal that is not unit length is normalised and the
  /// offset scaled with it, so the same set of points is meant.
  public init(normal: Vector3<Scalar>, offset: Scalar, materialIndex: Int = 0) {
    let length = normal.length
    self.normal = normal.normalized()
    self.offset = length.isNormal && length.isFinite ? offset / length : offset
    self.materialIndex = materialIndex
  }
}

extension Plane: Intersectable {
  /// The hit in (tMin, tMax), or nil: a ray parallel to the plane (n·d = 0)
  /// misses it, as does a ray starting on it (t = 0 is not > tMin ≥ 0).
  ///
  /// The stable method takes the plane relative to the ray's origin,
  /// k = d − n·o without cancellation, and n·d compensated at grazing
  /// angles (`PlaneIntersection.stableT`).
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    let t: Scalar?
    switch method {
    case .naive:
      t = PlaneIntersection.naiveT(
        normal: normal, offset: offset, origin: ray.origin,
        direction: ray.direction, after: tMin, before: tMax)
    case .stable:
      let distance: Scalar = CameraRelative.plane(
        normal: normal, offset: offset, eye: ray.origin)
      t = PlaneIntersection.stableT(
        normal: normal, normalTail: .zero, distance: distance,
        isAxisAligned: PlaneIntersection.isAxisAligned(normal),
        direction: ray.direction, after: tMin, before: tMax)
    }
    return t.map { Hit(t: $0, normal: normal, materialIndex: materialIndex) }
  }
}
