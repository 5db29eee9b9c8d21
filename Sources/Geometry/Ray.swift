/// A half-line origin + t·direction; the direction need not be unit length,
/// in which case t is measured in multiples of its length.
public struct Ray<Scalar: RayScalar>: Hashable, Sendable {
  public var origin: Vector3<Scalar>
  public var direction: Vector3<Scalar>

  @inlinable
  public init(origin: Vector3<Scalar>, direction: Vector3<Scalar>) {
    self.origin = origin
    self.direction = direction
  }

  @inlinable
  public func point(at t: Scalar) -> Vector3<Scalar> {
    origin + direction * t
  }
}
