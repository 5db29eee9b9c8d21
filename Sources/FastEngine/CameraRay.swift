import FastKernels
import Geometry

/// A camera ray as the render loop uses it: in the kernel's frame, with the
/// per-ray quantities every primitive test needs computed once.
package struct CameraRay<Scalar: RayScalar>: Sendable {
  /// The eye in the kernel's frame: the origin for camera-relative kernels.
  package var origin: Vector3<Scalar>
  package var direction: Vector3<Scalar>
  /// d·d, and its inverse: exactly 1 only when the rounded direction is
  /// exactly unit.
  package var lengthSquared: Scalar
  package var inverseLengthSquared: Scalar

  @inlinable
  package init(origin: Vector3<Scalar>, direction: Vector3<Scalar>) {
    self.origin = origin
    self.direction = direction
    lengthSquared = direction.lengthSquared
    inverseLengthSquared =
      SphereIntersection.inverseLengthSquared(lengthSquared)
  }
}
