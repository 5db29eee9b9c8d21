/// A camera ray as the render loop uses it: in the kernel's frame, with the
/// per-ray quantities every primitive test needs computed once.
public struct CameraRay<Scalar: RayScalar>: Sendable {
  /// The eye in the kernel's frame: the origin for camera-relative kernels.
  public var origin: Vector3<Scalar>
  public var direction: Vector3<Scalar>
  /// d·d, and its inverse: exactly 1 only when the rounded direction is
  /// exactly unit.
  public var lengthSquared: Scalar
  public var inverseLengthSquared: Scalar

  @inlinable
  public init(origin: Vector3<Scalar>, direction: Vector3<Scalar>) {
    self.origin = origin
    self.direction = direction
    lengthSquared = direction.lengthSquared
    // Camera rays are unit to within a few ulps: with a = 1 + δ, 2 − a is
    // 1/a to within δ² < ε once |δ| < 2^−26, and saves a division per ray.
    let deviation = lengthSquared - 1
    inverseLengthSquared =
      deviation.magnitude < 0x1p-26 ? 1 - deviation : 1 / lengthSquared
  }
}

/// The parts of the render loop that depend on the intersection method: how
/// spheres and planes are stored and tested. The loop is generic over it and
/// specialised for each method and precision, so no test dispatches
/// dynamically.
public protocol IntersectionKernel: Sendable {
  associatedtype Scalar: RayScalar
  associatedtype SphereRecord: Sendable
  associatedtype PlaneRecord: Sendable

  /// The eye's position in the frame the records are stored in.
  static func frameOrigin(eye: Vector3<Double>) -> Vector3<Scalar>
  static func makeSphere(_ sphere: Sphere<Double>, eye: Vector3<Double>) -> SphereRecord
  static func makePlane(_ plane: Plane<Double>, eye: Vector3<Double>) -> PlaneRecord
  /// The sphere's centre and radius in the kernel's frame, for the BVH.
  static func centerAndRadius(_ record: SphereRecord) -> (Vector3<Scalar>, Scalar)

  /// The nearest root in (0, tMax), or nil.
  static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar?
  static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar>
  static func intersect(
    _ record: PlaneRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar?
  static func normal(_ record: PlaneRecord) -> Vector3<Scalar>
}

/// The course's method in world coordinates, recomputing o − centre and
/// |f|² − r² for every ray in the render's precision, as the course does.
public enum NaiveKernel<Scalar: RayScalar>: IntersectionKernel {
  public struct SphereRecord: Sendable {
    var center: Vector3<Scalar>
    var radius: Scalar
  }

  public struct PlaneRecord: Sendable {
    var normal: Vector3<Scalar>
    var offset: Scalar
  }

  public static func frameOrigin(eye: Vector3<Double>) -> Vector3<Scalar> {
    Vector3(eye)
  }

  public static func makeSphere(
    _ sphere: Sphere<Double>, eye: Vector3<Double>
  ) -> SphereRecord {
    SphereRecord(center: Vector3(sphere.center), radius: Scalar(sphere.radius))
  }

  public static func makePlane(
    _ plane: Plane<Double>, eye: Vector3<Double>
  ) -> PlaneRecord {
    PlaneRecord(normal: Vector3(plane.normal), offset: Scalar(plane.offset))
  }

  public static func centerAndRadius(_ record: SphereRecord) -> (Vector3<Scalar>, Scalar) {
    (record.center, record.radius)
  }

  @inline(__always)
  public static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    SphereIntersection.naiveRoot(
      origin: ray.origin, direction: ray.direction, center: record.center,
      radius: record.radius, after: 0, before: tMax)
  }

  @inline(__always)
  public static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar> {
    SphereIntersection.naiveNormal(
      origin: ray.origin, direction: ray.direction, center: record.center, t: t)
  }

  @inline(__always)
  public static func intersect(
    _ record: PlaneRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    let denominator = record.normal.dot(ray.direction)
    guard denominator != 0 else { return nil }
    let t = (record.offset - record.normal.dot(ray.origin)) / denominator
    return t > 0 && t < tMax ? t : nil
  }

  public static func normal(_ record: PlaneRecord) -> Vector3<Scalar> {
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
public enum StableKernel<Scalar: RayScalar>: IntersectionKernel {
  public struct SphereRecord: Sendable {
    var offset: Vector3<Scalar>
    var radiusSquared: Scalar
    var c: Scalar
    var inverseRadius: Scalar
  }

  public struct PlaneRecord: Sendable {
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

  public static func frameOrigin(eye: Vector3<Double>) -> Vector3<Scalar> {
    .zero
  }

  public static func makeSphere(
    _ sphere: Sphere<Double>, eye: Vector3<Double>
  ) -> SphereRecord {
    let relative = CameraRelative.sphere(
      center: sphere.center, radius: sphere.radius, eye: eye, as: Scalar.self)
    let radius = Scalar(sphere.radius)
    return SphereRecord(
      offset: relative.offset, radiusSquared: radius * radius, c: relative.c,
      inverseRadius: 1 / radius)
  }

  public static func makePlane(
    _ plane: Plane<Double>, eye: Vector3<Double>
  ) -> PlaneRecord {
    let normal = Vector3<Scalar>(plane.normal)
    let tail: Vector3<Scalar> =
      Scalar.significandBitCount < Double.significandBitCount
      ? Vector3(plane.normal - Vector3<Double>(normal)) : .zero
    let distance: Scalar = CameraRelative.plane(
      normal: plane.normal, offset: plane.offset, eye: eye)
    let nonZero = [normal.x, normal.y, normal.z].filter { $0 != 0 }.count
    return PlaneRecord(
      normal: normal, normalTail: tail, distance: distance,
      isAxisAligned: nonZero == 1 && tail == .zero)
  }

  public static func centerAndRadius(_ record: SphereRecord) -> (Vector3<Scalar>, Scalar) {
    (record.offset, record.radiusSquared.squareRoot())
  }

  @inline(__always)
  public static func intersect(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    SphereIntersection.stableRoot(
      direction: ray.direction, lengthSquared: ray.lengthSquared,
      inverseLengthSquared: ray.inverseLengthSquared,
      offset: record.offset, c: record.c, radiusSquared: record.radiusSquared,
      after: 0, before: tMax)?.t
  }

  /// Camera rays start at t = 0, so the root hit is the entering one exactly
  /// when the eye is outside the sphere (c > 0): with c < 0 the smaller root
  /// is negative, and with c = 0 it is zero, which is not > 0.
  ///
  /// For a sphere closer than 64 radii (c < 4095 r²) the hit point's offset
  /// t·d − p is used directly: t's relative error ε becomes at most 64 ε in
  /// the normal's direction (10⁻¹⁴ rad in Double, 4·10⁻⁶ rad in Float),
  /// and it costs neither the closest-approach vector nor a square root.
  /// Farther spheres, where that offset cancels, take `stableNormal`.
  @inline(__always)
  public static func normal(
    _ record: SphereRecord, _ ray: CameraRay<Scalar>, t: Scalar
  ) -> Vector3<Scalar> {
    if record.c < 4095 * record.radiusSquared {
      let scaled = (ray.direction * t - record.offset) * record.inverseRadius
      let lengthSquared = scaled.lengthSquared
      if (lengthSquared - 1).magnitude < Scalar.ulpOfOne.squareRoot() {
        return scaled * (1.5 - 0.5 * lengthSquared)
      }
    }
    return SphereIntersection.stableNormal(
      direction: ray.direction, inverseLengthSquared: ray.inverseLengthSquared,
      offset: record.offset, radiusSquared: record.radiusSquared,
      inverseRadius: record.inverseRadius, entering: record.c > 0)
  }

  @inline(__always)
  public static func intersect(
    _ record: PlaneRecord, _ ray: CameraRay<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    // n·d in working precision errs by at most γ₃·Σ|nᵢdᵢ| ≤ 4ε for unit
    // vectors. Where |n·d| ≥ 1/4 that is a relative error of at most 16ε
    // (about 1ε in practice) and the plain product stands; a clear sign
    // against the plane's side is a miss; only rays within about 15° of
    // the plane, where n·d cancels, pay for the compensated product
    // (measured: it is three libm calls, 11 ns a ray, without FMA).
    let plain = record.normal.dot(ray.direction)
    let denominator: Scalar
    if plain.magnitude >= 0.25 || record.isAxisAligned {
      denominator = plain
    } else if plain.magnitude > 8 * Scalar.ulpOfOne
      && (plain > 0) != (record.distance > 0)
    {
      return nil
    } else {
      denominator =
        Compensated.dot(record.normal, ray.direction)
        + record.normalTail.dot(ray.direction)
    }
    guard denominator != 0 else { return nil }
    let t = record.distance / denominator
    return t > 0 && t < tMax ? t : nil
  }

  public static func normal(_ record: PlaneRecord) -> Vector3<Scalar> {
    record.normal
  }
}
