/// The nearest intersection of a ray with an object.
public struct Hit<Scalar: RayScalar>: Hashable, Sendable {
  /// Distance along the ray in multiples of its direction's length.
  public var t: Scalar
  /// Unit normal: outward for spheres, along the given normal for planes.
  public var normal: Vector3<Scalar>
  public var materialIndex: Int
  /// The texture coordinates (u, v) at the hit, for objects that have them
  /// (mesh triangles with `vt`); nil otherwise.
  public var textureCoordinate: TextureCoordinate<Scalar>?

  @inlinable
  public init(
    t: Scalar, normal: Vector3<Scalar>, materialIndex: Int,
    textureCoordinate: TextureCoordinate<Scalar>? = nil
  ) {
    self.t = t
    self.normal = normal
    self.materialIndex = materialIndex
    self.textureCoordinate = textureCoordinate
  }
}
