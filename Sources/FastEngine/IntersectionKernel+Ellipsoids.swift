import FastKernels
import ExactArithmetic
import Geometry
import SceneDescription

/// A sphere under a non-similarity transform, stored in its own space, the
/// course's way: rays carried there by M⁻¹ (the eye once, in Double; the
/// direction per ray by M⁻¹'s rows in the render's precision, not
/// renormalised, so t is the world t), the kernel's sphere test unchanged,
/// the normal brought back by M's cofactors.
///
/// The naive method's way for every ellipsoid, and the stable method's
/// for mild ones in Float (`StableEllipsoid`). Each row's dot product with
/// d loses ε·|d|/A_min, so this is the exact test of a direction moved by
/// about ε times the aspect A_max/A_min, and the sphere test in object
/// space loses ε times the eye's distance in radii to the closest
/// approach's cancellation: a disc of aspect 10⁶ loses hits and reverses
/// normals in Float.
package struct ObjectSpaceEllipsoid<Kernel: IntersectionKernel>: Sendable {
  package typealias Scalar = Kernel.Scalar
  var sphere: Kernel.SphereRecord
  /// The eye in object space, in the kernel's frame.
  var origin: Vector3<Scalar>
  /// The rows of M⁻¹'s linear part.
  var inverseRows: (Vector3<Scalar>, Vector3<Scalar>, Vector3<Scalar>)
  var matrix: Matrix4<Scalar>

  init(_ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>) {
    let objectEye = ellipsoid.inverse.transformPoint(eye)
    let inverse = Matrix4<Scalar>(ellipsoid.inverse)
    sphere = Kernel.makeSphere(ellipsoid.sphere, eye: objectEye)
    origin = Kernel.frameOrigin(eye: objectEye)
    inverseRows = (
      Vector3(inverse.m00, inverse.m01, inverse.m02),
      Vector3(inverse.m10, inverse.m11, inverse.m12),
      Vector3(inverse.m20, inverse.m21, inverse.m22)
    )
    matrix = Matrix4<Scalar>(ellipsoid.matrix)
  }

  @inline(__always)
  func localRay(_ ray: CameraRay<Scalar>) -> CameraRay<Scalar> {
    let d = ray.direction
    return CameraRay(
      origin: origin,
      direction: Vector3(
        inverseRows.0.dot(d), inverseRows.1.dot(d), inverseRows.2.dot(d)))
  }

  /// The sphere's root asked for without a bound, then compared with
  /// tMax: at a tangent the stable method's two roots can round out of
  /// order, and asked with tMax equal to the near one it answers with the
  /// far one, a few ulps nearer; the answer must not depend on tMax, or
  /// the ellipsoids' hierarchy (which asks with its ties' bound) and the
  /// search one by one find different ellipsoids.
  @inline(__always)
  func intersect(_ ray: CameraRay<Scalar>, before tMax: Scalar) -> Scalar? {
    guard let t = Kernel.intersect(sphere, localRay(ray), before: .infinity)
    else { return nil }
    return t < tMax ? t : nil
  }

  /// Inlined where it is called, as it was before it had a type of its
  /// own: called out of line, the naive method's normal took a fifth more
  /// time on a scene an ellipsoid fills.
  @inline(__always)
  func normal(_ ray: CameraRay<Scalar>, t: Scalar) -> Vector3<Scalar> {
    matrix.transformNormal(Kernel.normal(sphere, localRay(ray), t: t))
  }
}

extension NaiveKernel {
  package typealias EllipsoidRecord = ObjectSpaceEllipsoid<NaiveKernel>

  package static func makeEllipsoid(
    _ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>
  ) -> EllipsoidRecord {
    ObjectSpaceEllipsoid(ellipsoid, eye: eye)
  }

  @inline(__always)
  package static func intersect(
    _ record: EllipsoidRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    record.intersect(ray, before: tMax)
  }

  @inline(__always)
  package static func normal(
    _ record: EllipsoidRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar> {
    record.normal(ray, t: t)
  }
}

/// The stable method's ellipsoid: in the frame of its principal axes, each
/// divided by its semi-axis (`EllipsoidFrame`), with the centre relative
/// to the eye computed once in DoubleDouble; per ray, the local direction
/// by one dot product and one product per axis and the stable quadratic
/// with the closest approach's cancellation taken out. Hits, t and normals
/// are within a few ulps of the exact ones for a ray within a few ulps of
/// the camera ray, at every aspect (see EllipsoidFrame+Intersection.swift).
///
/// Mild ellipsoids in Float keep the object-space test
/// (`ObjectSpaceEllipsoid`, `isMild`), which the project's Float images
/// were drawn with, and which is as accurate there. Both are stored and a
/// flag chooses, rather than an enum: a search copied the enum's payload
/// out of the array on every test, which made an ellipsoid's test twice
/// as slow.
package struct StableEllipsoid<Scalar: RayScalar>: Sendable {
  var usesObjectSpace: Bool
  var frame: EllipsoidFrame<Scalar>
  var objectSpace: ObjectSpaceEllipsoid<StableKernel<Scalar>>

  init(_ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>) {
    objectSpace = ObjectSpaceEllipsoid(ellipsoid, eye: eye)
    guard
      let axes = EllipsoidAxes(
        matrix: ellipsoid.matrix, sphere: ellipsoid.sphere)
    else {
      (usesObjectSpace, frame) = (false, .never)
      return
    }
    usesObjectSpace = Self.isMild(axes, eye: eye)
    frame = EllipsoidFrame(axes, eye: eye) ?? .never
  }

  /// Whether the object-space test is exact to a few ulps for `axes` seen
  /// from `eye` in S, and so is kept: S narrower than Double (the eye is
  /// carried into object space in Double, so its rounding is below S's),
  /// aspect A_max/A_min ≤ 8 (the rows of M⁻¹ then lose at most 8·ε·|d| of
  /// the direction), and the eye within 64 radii of the centre in object
  /// space (|p|² < 4096, where the sphere test's closest approach loses at
  /// most 64 ε and its normal takes the hit's offset directly). The
  /// project's scenes' ellipsoids (aspect 1.7 to 5, 10 to 20 radii away)
  /// are all mild.
  static func isMild(
    _ axes: EllipsoidAxes, eye: Vector3<Double>
  ) -> Bool {
    guard Scalar.significandBitCount < Double.significandBitCount,
      let shortest = axes.lengths.min(), let longest = axes.lengths.max(),
      longest <= 8 * shortest
    else { return false }
    let relative = axes.center - Vector3<DoubleDouble>(eye)
    let squared = (0..<3).map { j in
      let p = axes.directions[j].dot(relative) / axes.lengths[j]
      return p * p
    }
    return squared[0] + squared[1] + squared[2] < 4096
  }
}

extension StableKernel {
  package typealias EllipsoidRecord = StableEllipsoid<Scalar>

  package static func makeEllipsoid(
    _ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>
  ) -> EllipsoidRecord {
    StableEllipsoid(ellipsoid, eye: eye)
  }

  @inline(__always)
  package static func intersect(
    _ record: EllipsoidRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    record.usesObjectSpace
      ? record.objectSpace.intersect(ray, before: tMax)
      : record.frame.root(direction: ray.direction, before: tMax)
  }

  /// Out of line: the normal of every other kind is computed in the same
  /// function (`CompiledScene.normal(of:)`), which it would otherwise
  /// grow by both forms' code.
  @inline(never)
  package static func normal(
    _ record: EllipsoidRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar> {
    record.usesObjectSpace
      ? record.objectSpace.normal(ray, t: t)
      : record.frame.normal(direction: ray.direction, t: t)
  }
}
