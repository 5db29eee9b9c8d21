import Geometry

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
