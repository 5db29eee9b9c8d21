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
  /// Both d − n·o and n·d are evaluated compensated: the first cancels when the
  /// origin is near the plane, the second at grazing angles.
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Hit<Scalar>? {
    let distance: Scalar = CameraRelative.plane(
      normal: normal, offset: offset, eye: ray.origin)
    let denominator = Compensated.dot(normal, ray.direction)
    guard denominator != 0 else { return nil }
    let t = distance / denominator
    guard t > tMin && t < tMax else { return nil }
    return Hit(t: t, normal: normal, materialIndex: materialIndex)
  }
}
