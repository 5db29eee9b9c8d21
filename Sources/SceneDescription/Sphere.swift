import Geometry

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
