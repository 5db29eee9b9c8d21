import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

final class PlaneMethodTests: XCTestCase {
  /// The ground plane y = 0 and the plane y = −1.2 (a negative offset).
  func checkHitFromEitherSide<T: RayScalar>(_: T.Type) {
    let ground = Plane<T>(normal: Vector3(0, 1, 0), offset: 0, materialIndex: 2)
    let above = Ray<T>(origin: Vector3(1, 3, -2), direction: Vector3(0, -1, 0))
    let below = Ray<T>(origin: Vector3(1, -2, -2), direction: Vector3(0, 1, 0))
    let fromAbove = ground.intersect(above, after: 0, before: .infinity)
    XCTAssertEqual(fromAbove?.t, 3, "\(T.self): exact, small integers")
    XCTAssertEqual(fromAbove?.normal, Vector3(0, 1, 0))
    XCTAssertEqual(fromAbove?.materialIndex, 2)
    let fromBelow = ground.intersect(below, after: 0, before: .infinity)
    XCTAssertEqual(fromBelow?.t, 2, "\(T.self): exact, small integers")
    XCTAssertEqual(
      fromBelow?.normal, Vector3(0, 1, 0), "\(T.self): as given, not flipped")

    let lowered = Plane<T>(normal: Vector3(0, 1, 0), offset: -1.2)
    let down = Ray<T>(origin: .zero, direction: Vector3(0, -1, 0))
    // t = −1.2/−1: the offset is the only rounded value, and t is it.
    XCTAssertEqual(lowered.intersect(down, after: 0, before: .infinity)?.t, 1.2)
  }

  func testIntersect_FromEitherSide_Float() {
    checkHitFromEitherSide(Float.self)
  }
  func testIntersect_FromEitherSide_Double() {
    checkHitFromEitherSide(Double.self)
  }

  /// n·d = 0: a ray parallel to the plane misses, whether above it or lying
  /// in it (0/0 must not become a hit).
  func checkParallel<T: RayScalar>(_: T.Type) {
    let plane = Plane<T>(normal: Vector3(0, 1, 0), offset: 0)
    let rays = [
      Ray<T>(origin: Vector3(0, 1, 0), direction: Vector3(1, 0, 0)),
      Ray<T>(origin: Vector3(0, -1, 0), direction: Vector3(0, 0, -3)),
      Ray<T>(origin: Vector3(4, 0, 4), direction: Vector3(1, 0, 1)),
    ]
    for ray in rays {
      XCTAssertNil(
        plane.intersect(ray, after: 0, before: .infinity), "\(T.self) \(ray)")
    }
  }

  func testIntersect_Parallel_Float() { checkParallel(Float.self) }
  func testIntersect_Parallel_Double() { checkParallel(Double.self) }

  /// The plane behind the ray (t = −1) is missed.
  func checkBehind<T: RayScalar>(_: T.Type) {
    let plane = Plane<T>(normal: Vector3(0, 1, 0), offset: 0)
    let ray = Ray<T>(origin: Vector3(0, 1, 0), direction: Vector3(0, 1, 0))
    XCTAssertNil(plane.intersect(ray, after: 0, before: .infinity), "\(T.self)")
  }

  func testIntersect_Behind_Float() { checkBehind(Float.self) }
  func testIntersect_Behind_Double() { checkBehind(Double.self) }

  /// A ray from a point exactly on the plane has t = ±0, not > tMin = 0.
  func checkOriginOnPlane<T: RayScalar>(_: T.Type) {
    let plane = Plane<T>(normal: Vector3(0, 0, 1), offset: 3)
    for direction in [
      Vector3<T>(0, 0, 1), Vector3(0, 0, -1), Vector3(1, 2, -3),
    ] {
      let ray = Ray<T>(origin: Vector3(1, 2, 3), direction: direction)
      XCTAssertNil(
        plane.intersect(ray, after: 0, before: .infinity),
        "\(T.self) \(direction)")
    }
  }

  func testIntersect_OriginOnPlane_Float() { checkOriginOnPlane(Float.self) }
  func testIntersect_OriginOnPlane_Double() { checkOriginOnPlane(Double.self) }

  /// Plane(normal: (0, 2, 0), offset: 4) is y = 2: the normal is normalised
  /// and the offset divided by the same length.
  func checkNonUnitNormal<T: RayScalar>(_: T.Type) {
    let plane = Plane<T>(normal: Vector3(0, 2, 0), offset: 4)
    XCTAssertEqual(plane.normal, Vector3(0, 1, 0), "\(T.self)")
    XCTAssertEqual(plane.offset, 2, "\(T.self)")
    let up = Ray<T>(origin: .zero, direction: Vector3(0, 1, 0))
    let hit = plane.intersect(up, after: 0, before: .infinity)
    XCTAssertEqual(hit?.t, 2, "\(T.self)")
    XCTAssertEqual(hit?.normal, Vector3(0, 1, 0), "\(T.self)")

    // 3x + 4y = 10 is the plane at distance 2 along (0.6, 0.8, 0); the
    // normal and offset are each rounded once or twice.
    let oblique = Plane<T>(normal: Vector3(3, 4, 0), offset: 10)
    assertRelativeError(oblique.offset, 2, ulps: 1, "10/5, one rounding")
    assertRelativeError(
      oblique.normal, Vector3(0.6, 0.8, 0), ulps: 1,
      "(3, 4)/5, one rounding each")
    let along = Ray<T>(origin: .zero, direction: Vector3(3, 4, 0))
    if let hit = oblique.intersect(along, after: 0, before: .infinity) {
      // t = 2/5 in multiples of |d| = 5; four roundings at most.
      assertRelativeError(hit.t, 0.4, ulps: 2, "offset, n·d, quotient")
    } else {
      XCTFail("\(T.self): the ray along the normal must hit")
    }
  }

  func testInit_NonUnitNormal_Float() { checkNonUnitNormal(Float.self) }
  func testInit_NonUnitNormal_Double() { checkNonUnitNormal(Double.self) }

  /// The hit must lie in the open interval (tMin, tMax); t scales with 1/|d|.
  func checkInterval<T: RayScalar>(_: T.Type) {
    let plane = Plane<T>(normal: Vector3(0, 1, 0), offset: 0)
    let ray = Ray<T>(origin: Vector3(0, 3, 0), direction: Vector3(0, -1, 0))
    XCTAssertEqual(plane.intersect(ray, after: 0, before: 3.5)?.t, 3)
    XCTAssertNil(plane.intersect(ray, after: 0, before: 3))
    XCTAssertNil(plane.intersect(ray, after: 3, before: .infinity))
    let fast = Ray<T>(origin: Vector3(0, 3, 0), direction: Vector3(0, -4, 0))
    XCTAssertEqual(plane.intersect(fast, after: 0, before: .infinity)?.t, 0.75)
  }

  func testIntersect_Interval_Float() { checkInterval(Float.self) }
  func testIntersect_Interval_Double() { checkInterval(Double.self) }

  /// Grazing incidence with an exact answer: n = (1, 1, 0)/√2 rounded (both
  /// components the same value h), o = (1, 0, 0), d = (−1, 1 − 2^−k, 0), so
  /// n·d = −h·2^−k and offset − n·o = −h are exact in T and t = 2^k
  /// exactly. Plain evaluation of n·d would round h·(1 − 2^−k) and be off
  /// by up to 2^(k−p) relatively.
  func checkGrazingExact<T: RayScalar>(_: T.Type) {
    let plane = Plane<T>(normal: Vector3(1, 1, 0), offset: 0)
    XCTAssertEqual(plane.normal.x, plane.normal.y)
    let origin = Vector3<T>(1, 0, 0)
    var plainWorst = 0.0
    for k in 1...T.significandBitCount {
      let step = T(sign: .plus, exponent: T.Exponent(-k), significand: 1)
      let ray = Ray(origin: origin, direction: Vector3(-1, 1 - step, 0))
      let want = T(sign: .plus, exponent: T.Exponent(k), significand: 1)
      XCTAssertEqual(
        plane.intersect(ray, after: 0, before: .infinity)?.t, want,
        "\(T.self): 1/2^−k, k = \(k)")
      let plain = -plane.normal.dot(origin) / plane.normal.dot(ray.direction)
      plainWorst = max(
        plainWorst, relativeErrorInUlps(plain, ReferenceScalar(want)))
    }
    // The uncompensated formula must be visibly wrong here, or this test
    // would not tell the two apart.
    XCTAssertGreaterThan(plainWorst, 1e3, "\(T.self): plain n·d")
  }

  func testIntersect_GrazingExact_Float() { checkGrazingExact(Float.self) }
  func testIntersect_GrazingExact_Double() { checkGrazingExact(Double.self) }

  /// Random planes and rays at grazing angles (n·d log-uniform in
  /// [1e−6, 0.1]) from points near the plane, in Float against the Float80
  /// reference, which is exact but for its last roundings here (products of
  /// Floats are exact in 64 bits; sums lose 2^−64 of their largest term).
  func testIntersect_GrazingRandom_Float() {
    var worst = (compensated: 0.0, plain: 0.0)
    forEachSeed(2000, base: 0x9A1E_0001) { generator, seed in
      let normal = generator.unitVector(Float.self)
      let offset = generator.sign(Float.self) * generator.logUniform(1e-2, 1e2)
      let plane = Plane(normal: normal, offset: offset)
      let tangent = normal.cross(generator.unitVector(Float.self)).normalized()
      let slope: Float = generator.logUniform(1e-6, 1e-1)
      let height: Float = generator.logUniform(1e-2, 10)
      // A point on the plane (up to rounding), lifted by `height` and sent
      // back down at the grazing slope.
      let foot =
        plane.normal * plane.offset + tangent * generator.uniform(-50...50)
      let origin = foot + plane.normal * height
      let ray = Ray(origin: origin, direction: tangent - plane.normal * slope)
      guard let want = referenceIntersect(ray, plane) else {
        XCTFail("seed \(seed): the reference must hit")
        return
      }
      guard let hit = plane.intersect(ray, after: 0, before: .infinity) else {
        XCTFail("seed \(seed): must hit, reference t = \(want.t)")
        return
      }
      // offset − n·o and n·d are each rounded once (Sum2 and Dot2 add
      // γ²·cond ≤ 0.5 ulp at these condition numbers), then divided:
      // budget 3 ulps; measured worst 1.2.
      worst.compensated = max(
        worst.compensated,
        assertRelativeError(hit.t, want.t, ulps: 3, "seed \(seed)"))
      XCTAssertEqual(hit.normal, plane.normal, "seed \(seed): as given")
      let plain =
        (plane.offset - plane.normal.dot(origin))
        / plane.normal.dot(ray.direction)
      worst.plain = max(worst.plain, relativeErrorInUlps(plain, want.t))
    }
    print("Float grazing plane worst: \(worst)")
    // The uncompensated formula loses cond·ε; measured worst 2.3e5 ulps.
    XCTAssertGreaterThan(worst.plain, 1e3, "plain evaluation at grazing angles")
  }
}
