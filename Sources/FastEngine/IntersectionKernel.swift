import FastKernels
import Geometry
import SceneDescription

/// The parts of the render loop that depend on the intersection method: how
/// spheres and planes are stored and tested. The loop is generic over it and
/// specialised for each method and precision, so no test dispatches
/// dynamically.
package protocol IntersectionKernel: Sendable {
  associatedtype Scalar: RayScalar
  associatedtype SphereRecord: Sendable
  associatedtype PlaneRecord: Sendable

  /// The eye's position in the frame the records are stored in.
  static func frameOrigin(eye: Vector3<Double>) -> Vector3<Scalar>
  static func makeSphere(_ sphere: Sphere<Double>, eye: Vector3<Double>)
    -> SphereRecord
  static func makePlane(_ plane: Plane<Double>, eye: Vector3<Double>)
    -> PlaneRecord
  /// The sphere's centre and radius in the kernel's frame, for the BVH.
  static func centerAndRadius(_ record: SphereRecord) -> (
    Vector3<Scalar>, Scalar
  )

  /// The nearest root in (0, tMax), or nil.
  static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar?
  static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar>

  /// What a sphere test computes on its way to t that the hit's normal
  /// would compute again (the stable method's closest approach); nothing
  /// for the naive method. The flat searches keep the nearest hit's.
  associatedtype SphereHitMemo: Sendable
  /// The memo before any test: the normal computes everything itself.
  static var noMemo: SphereHitMemo { get }
  /// `intersect`, also writing what its normal can reuse into `memo` on a
  /// hit.
  static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar,
    memo: inout SphereHitMemo
  ) -> Scalar?
  /// `normal` from the memo of the test that found t: the same bits.
  static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar,
    memo: SphereHitMemo
  ) -> Vector3<Scalar>

  static func intersect(
    _ record: PlaneRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar?
  static func normal(_ record: PlaneRecord) -> Vector3<Scalar>

  /// A sphere under a transform that is not a similarity (an ellipsoid),
  /// as the method stores it (IntersectionKernel+Ellipsoids.swift).
  associatedtype EllipsoidRecord: Sendable
  static func makeEllipsoid(
    _ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>
  ) -> EllipsoidRecord
  /// The nearest root in (0, tMax) of a camera ray, in the world's t, or
  /// nil.
  static func intersect(
    _ record: EllipsoidRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar?
  /// The outward unit normal in the world at the root t of `intersect`.
  static func normal(
    _ record: EllipsoidRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar>
}

/// The course's method in world coordinates, recomputing o − centre and
/// |f|² − r² for every ray in the render's precision, as the course does.
package enum NaiveKernel<Scalar: RayScalar>: IntersectionKernel {
  package struct SphereRecord: Sendable {
    var center: Vector3<Scalar>
    var radius: Scalar
  }

  package struct PlaneRecord: Sendable {
    var normal: Vector3<Scalar>
    var offset: Scalar
  }

  package static func frameOrigin(eye: Vector3<Double>) -> Vector3<Scalar> {
    Vector3(eye)
  }

  package static func makeSphere(
    _ sphere: Sphere<Double>, eye: Vector3<Double>
  ) -> SphereRecord {
    SphereRecord(center: Vector3(sphere.center), radius: Scalar(sphere.radius))
  }

  package static func makePlane(
    _ plane: Plane<Double>, eye: Vector3<Double>
  ) -> PlaneRecord {
    PlaneRecord(normal: Vector3(plane.normal), offset: Scalar(plane.offset))
  }

  package static func centerAndRadius(_ record: SphereRecord) -> (
    Vector3<Scalar>, Scalar
  ) {
    (record.center, record.radius)
  }

  @inline(__always)
  package static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    SphereIntersection.naiveRoot(
      origin: ray.origin, direction: ray.direction, center: record.center,
      radius: record.radius, after: 0, before: tMax)
  }

  package static var noMemo: Void { () }

  @inline(__always)
  package static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar,
    memo: inout Void
  ) -> Scalar? {
    intersect(record, ray, before: tMax)
  }

  @inline(__always)
  package static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar, memo: Void
  ) -> Vector3<Scalar> {
    normal(record, ray, t: t)
  }

  @inline(__always)
  package static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar> {
    SphereIntersection.naiveNormal(
      origin: ray.origin, direction: ray.direction, center: record.center, t: t)
  }

  @inline(__always)
  package static func intersect(
    _ record: PlaneRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    PlaneIntersection.naiveT(
      normal: record.normal, offset: record.offset, origin: ray.origin,
      direction: ray.direction, after: 0, before: tMax)
  }

  package static func normal(_ record: PlaneRecord) -> Vector3<Scalar> {
    record.normal
  }
}

/// The stable method, camera-relative: the eye is the origin, each sphere is
/// stored as p = centre − eye with c = |p|² − r² and each plane's distance
/// from the eye as k = d − n·eye, all computed once in twice Double's
/// precision (`CameraRelative`) and rounded once to the render's precision.
/// Per ray that leaves only the cancellation-free quadratic of
/// `SphereIntersection.stableRoot` and, for planes, a compensated n·d with
/// the normal carried to twice the render's precision.
package enum StableKernel<Scalar: RayScalar>: IntersectionKernel {
  package struct SphereRecord: Sendable {
    var offset: Vector3<Scalar>
    var radiusSquared: Scalar
    var c: Scalar
    var inverseRadius: Scalar
  }

  package struct PlaneRecord: Sendable {
    var normal: Vector3<Scalar>
    /// normal − Scalar(normal) in the scene's Double: zero for Double
    /// renders, the rest of the normal's digits for Float ones, so that a
    /// grazing plane keeps its orientation.
    var normalTail: Vector3<Scalar>
    var distance: Scalar
    /// Whether n·d is a single product (one non-zero component, no tail):
    /// then it is correctly rounded and never cancels, grazing or not.
    var isAxisAligned: Bool
  }

  package static func frameOrigin(eye: Vector3<Double>) -> Vector3<Scalar> {
    .zero
  }

  package static func makeSphere(
    _ sphere: Sphere<Double>, eye: Vector3<Double>
  ) -> SphereRecord {
    let relative = CameraRelative.sphere(
      center: sphere.center, radius: sphere.radius, eye: eye, as: Scalar.self)
    let radius = Scalar(sphere.radius)
    return SphereRecord(
      offset: relative.offset, radiusSquared: radius * radius, c: relative.c,
      inverseRadius: 1 / radius)
  }

  package static func makePlane(
    _ plane: Plane<Double>, eye: Vector3<Double>
  ) -> PlaneRecord {
    let normal = Vector3<Scalar>(plane.normal)
    let tail: Vector3<Scalar> =
      Scalar.significandBitCount < Double.significandBitCount
      ? Vector3(plane.normal - Vector3<Double>(normal)) : .zero
    let distance: Scalar = CameraRelative.plane(
      normal: plane.normal, offset: plane.offset, eye: eye)
    return PlaneRecord(
      normal: normal, normalTail: tail, distance: distance,
      isAxisAligned: PlaneIntersection.isAxisAligned(normal) && tail == .zero)
  }

  package static func centerAndRadius(_ record: SphereRecord) -> (
    Vector3<Scalar>, Scalar
  ) {
    (record.offset, record.radiusSquared.squareRoot())
  }

  @inline(__always)
  package static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    var memo = noMemo
    return root(record, ray, before: tMax, memo: &memo)
  }

  package static var noMemo: SphereIntersection.ClosestApproach<Scalar>? {
    nil
  }

  /// The flat searches' test (every sphere, or those culled per tile),
  /// which meets spheres behind the eye too: a sphere whose centre is
  /// behind the eye (p·d < 0) while the eye is outside it (c > 0) has both
  /// roots negative (their product c/a is positive, their sum 2 p·d/a is
  /// not), and so does `stableRoot` as it computes them (q < 0, c > 0), so
  /// it is rejected first. Not in `stableRoot` itself: there it made the
  /// screen tiles' sphere loop, which never meets such spheres, 40% slower.
  @inline(__always)
  package static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar,
    memo: inout SphereIntersection.ClosestApproach<Scalar>?
  ) -> Scalar? {
    if record.c > 0 && record.offset.dot(ray.direction) < 0 { return nil }
    return root(record, ray, before: tMax, memo: &memo)
  }

  @inline(__always)
  static func root(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar,
    memo: inout SphereIntersection.ClosestApproach<Scalar>?
  ) -> Scalar? {
    SphereIntersection.stableRoot(
      direction: ray.direction, lengthSquared: ray.lengthSquared,
      inverseLengthSquared: ray.inverseLengthSquared,
      offset: record.offset, c: record.c, radiusSquared: record.radiusSquared,
      after: 0, before: tMax, approach: &memo)?.t
  }

  /// Camera rays start at t = 0, so the root hit is the entering one exactly
  /// when the eye is outside the sphere (c > 0): with c < 0 the smaller root
  /// is negative, and with c = 0 it is zero, which is not > 0.
  @inline(__always)
  package static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar> {
    normal(record, ray, t: t, memo: noMemo)
  }

  @inline(__always)
  package static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar,
    memo: SphereIntersection.ClosestApproach<Scalar>?
  ) -> Vector3<Scalar> {
    SphereIntersection.stableNormal(
      direction: ray.direction, lengthSquared: ray.lengthSquared,
      inverseLengthSquared: ray.inverseLengthSquared, t: t,
      offset: record.offset, c: record.c,
      radiusSquared: record.radiusSquared, inverseRadius: record.inverseRadius,
      entering: record.c > 0, approach: memo)
  }

  @inline(__always)
  package static func intersect(
    _ record: PlaneRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    PlaneIntersection.stableT(
      normal: record.normal, normalTail: record.normalTail,
      distance: record.distance, isAxisAligned: record.isAxisAligned,
      direction: ray.direction, after: 0, before: tMax)
  }

  package static func normal(_ record: PlaneRecord) -> Vector3<Scalar> {
    record.normal
  }
}
