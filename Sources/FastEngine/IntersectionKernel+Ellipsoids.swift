import SceneIO
import SceneModel

/// A sphere under a non-similarity transform, the course's way, for the
/// naive method: stored in its own space, rays carried there by M⁻¹
/// (the eye once, in Double; the direction per ray by M⁻¹'s rows in the
/// render's precision, not renormalised, so t is the world t), the naive
/// sphere test unchanged, the normal brought back by M's cofactors.
public struct CourseEllipsoidRecord<Scalar: RayScalar>: Sendable {
  var sphere: NaiveKernel<Scalar>.SphereRecord
  /// The eye in object space.
  var origin: Vector3<Scalar>
  /// The rows of M⁻¹'s linear part.
  var inverseRows: (Vector3<Scalar>, Vector3<Scalar>, Vector3<Scalar>)
  var matrix: Matrix4<Scalar>

  @inline(__always)
  func localRay(_ ray: CameraRay<Scalar>) -> CameraRay<Scalar> {
    let d = ray.direction
    return CameraRay(
      origin: origin,
      direction: Vector3(
        inverseRows.0.dot(d), inverseRows.1.dot(d), inverseRows.2.dot(d)))
  }
}

extension NaiveKernel {
  public typealias EllipsoidRecord = CourseEllipsoidRecord<Scalar>

  public static func makeEllipsoid(
    _ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>
  ) -> CourseEllipsoidRecord<Scalar> {
    let objectEye = ellipsoid.inverse.transformPoint(eye)
    let inverse = Matrix4<Scalar>(ellipsoid.inverse)
    return CourseEllipsoidRecord(
      sphere: makeSphere(ellipsoid.sphere, eye: objectEye),
      origin: frameOrigin(eye: objectEye),
      inverseRows: (
        Vector3(inverse.m00, inverse.m01, inverse.m02),
        Vector3(inverse.m10, inverse.m11, inverse.m12),
        Vector3(inverse.m20, inverse.m21, inverse.m22)
      ),
      matrix: Matrix4<Scalar>(ellipsoid.matrix))
  }

  @inline(__always)
  public static func intersect(
    _ record: CourseEllipsoidRecord<Scalar>, _ ray: CameraRay<Scalar>,
    before tMax: Scalar
  ) -> Scalar? {
    intersect(record.sphere, record.localRay(ray), before: tMax)
  }

  public static func normal(
    _ record: CourseEllipsoidRecord<Scalar>, _ ray: CameraRay<Scalar>,
    t: Scalar
  ) -> Vector3<Scalar> {
    record.matrix.transformNormal(
      normal(record.sphere, record.localRay(ray), t: t))
  }
}

/// The stable method: the ellipsoid in the frame of its principal axes,
/// each divided by its semi-axis (`EllipsoidFrame`), with the centre
/// relative to the eye computed once in DoubleDouble; per ray, the local
/// direction by one dot product and one product per axis and the stable
/// quadratic with the closest approach's cancellation taken out. Hits, t
/// and normals are within a few ulps of the exact ones for a ray within a
/// few ulps of the camera ray, at every aspect (see
/// EllipsoidFrame+Intersection.swift).
extension StableKernel {
  public typealias EllipsoidRecord = EllipsoidFrame<Scalar>

  public static func makeEllipsoid(
    _ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>
  ) -> EllipsoidFrame<Scalar> {
    EllipsoidFrame(ellipsoid, eye: eye)
  }

  @inline(__always)
  public static func intersect(
    _ record: EllipsoidFrame<Scalar>, _ ray: CameraRay<Scalar>,
    before tMax: Scalar
  ) -> Scalar? {
    record.root(direction: ray.direction, before: tMax)
  }

  public static func normal(
    _ record: EllipsoidFrame<Scalar>, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar> {
    record.normal(direction: ray.direction, t: t)
  }
}
