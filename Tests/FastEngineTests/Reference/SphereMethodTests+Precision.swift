import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension SphereMethodTests {
  // MARK: - Precision: where the naive formula fails

  /// A small far sphere: radius 1 at distance L, the ray along the axis.
  /// t = L − 1 is exact in T; the naive discriminant b² − 4ac cancels
  /// completely once L/r ≳ ε^(−1/2), and its t is off by up to r/L.
  func checkSmallFarSphereOnAxis<T: RayScalar>(_: T.Type, distance: T) {
    let sphere = Sphere<T>(center: Vector3(0, 0, -distance), radius: 1)
    let ray = Ray<T>(origin: .zero, direction: Vector3(0, 0, -1))
    guard
      let stable = sphere.intersect(
        ray, after: 0, before: .infinity, method: .stable)
    else {
      XCTFail("\(T.self): the stable method must hit")
      return
    }
    // L − 1 is exact in T, but c = L² − 1 is not: rounded once (½ ulp),
    // then divided by q = L + 1 (½ ulp). Budget 1.5 ulps.
    assertRelativeError(
      stable.t, ReferenceScalar(distance - 1), ulps: 1.5, "c and c/q rounded")
    XCTAssertEqual(stable.normal, Vector3(0, 0, 1), "l = 0 exactly on the axis")
    let naive = sphere.intersect(
      ray, after: 0, before: .infinity, method: .naive)
    XCTAssertNotEqual(
      naive?.t, distance - 1,
      "\(T.self): the naive formula was expected to fail here; if it no "
        + "longer does, the precision tests below have lost their point")
  }

  /// The protocol's entry point (and so Group and the renderer's model)
  /// uses the stable method: on a small far sphere, where the methods
  /// differ, it returns the stable hit.
  func checkDefaultIsStable<T: RayScalar>(_: T.Type, distance: T) {
    let sphere = Sphere<T>(center: Vector3(0.25, 0, -distance), radius: 1)
    let ray = Ray<T>(origin: .zero, direction: Vector3(0, 0.125, -distance))
    let stable = sphere.intersect(
      ray, after: 0, before: .infinity, method: .stable)
    let naive = sphere.intersect(
      ray, after: 0, before: .infinity, method: .naive)
    XCTAssertNotEqual(stable, naive, "\(T.self): the methods must differ here")
    XCTAssertEqual(sphere.intersect(ray, after: 0, before: .infinity), stable)
  }

  func testIntersect_DefaultIsStable_Float() {
    checkDefaultIsStable(Float.self, distance: 1e4)
  }
  func testIntersect_DefaultIsStable_Double() {
    checkDefaultIsStable(Double.self, distance: 1e8)
  }

  func testPrecision_SmallFarSphereOnAxis_Float() {
    checkSmallFarSphereOnAxis(Float.self, distance: 1e4)
  }
  func testPrecision_SmallFarSphereOnAxis_Double() {
    checkSmallFarSphereOnAxis(Double.self, distance: 1e8)
  }

  /// The same small far sphere hit off-axis: rays from the origin aimed at
  /// random points within 0.9 r of the centre, against the reference. The
  /// centre has integer coordinates so that the Double reference is exact.
  func checkSmallFarSphere<T: RayScalar>(
    _: T.Type, distance: T, stableBudget: Double, base: UInt64
  ) -> (stable: Double, naive: Double) {
    var worst = (stable: 0.0, naive: 0.0)
    forEachSeed(1000, base: base) { generator, seed in
      let centre = Vector3<T>(
        T(Int.random(in: -3...3, using: &generator)),
        T(Int.random(in: -3...3, using: &generator)), -distance)
      let sphere = Sphere(center: centre, radius: 1)
      let aim =
        centre
        + generator.unitVector(T.self) * generator.uniform(0...0.9, as: T.self)
      let ray = Ray(origin: .zero, direction: aim)
      guard let want = referenceIntersect(ray, sphere),
        let stable = sphere.intersect(
          ray, after: 0, before: .infinity, method: .stable)
      else {
        XCTFail("seed \(seed): the reference and the stable method must hit")
        return
      }
      worst.stable = max(
        worst.stable,
        assertRelativeError(
          stable.t, want.t, ulps: stableBudget, "stable, seed \(seed)"))
      let naive = sphere.intersect(
        ray, after: 0, before: .infinity, method: .naive)
      worst.naive = max(
        worst.naive,
        naive.map { relativeErrorInUlps($0.t, want.t) } ?? .infinity)
      // Outward and unit length even where the normal's direction itself
      // is ill-conditioned (it moves by L·ε/r per ulp of d).
      XCTAssertGreaterThan(
        stable.normal.dot(ray.point(at: stable.t) - centre), 0)
      XCTAssertEqual(
        Double(stable.normal.length), 1, accuracy: 2 * Double(T.ulpOfOne),
        "seed \(seed): unit normal, 2 ulps")
    }
    print("\(T.self) small far sphere L/r = \(distance) worst: \(worst)")
    return worst
  }

  func testPrecision_SmallFarSphere_Float() {
    // Measured worst of t: stable 1.3 ulps at L/r = 1e4, 0.7 at 1e6; the
    // naive method misses some of these rays outright (error ∞).
    for (distance, base): (Float, UInt64) in [
      (1e4, 0x5EED_0005), (1e6, 0x5EED_0015),
    ] {
      let worst = checkSmallFarSphere(
        Float.self, distance: distance, stableBudget: 4, base: base)
      XCTAssertGreaterThan(
        worst.naive, 1e3,
        "the naive formula was expected to fail at L/r = \(distance)")
    }
  }

  func testPrecision_SmallFarSphere_Double() {
    // Measured worst of t: stable 1.8 ulps at L/r = 1e8, 0.9 at 1e10; the
    // naive method misses some of these rays outright (error ∞).
    for (distance, base): (Double, UInt64) in [
      (1e8, 0x5EED_0006), (1e10, 0x5EED_0016),
    ] {
      let worst = checkSmallFarSphere(
        Double.self, distance: distance, stableBudget: 4, base: base)
      XCTAssertGreaterThan(
        worst.naive, 1e3,
        "the naive formula was expected to fail at L/r = \(distance)")
    }
  }

  /// A huge sphere seen from close by: the eye at height h above a sphere of
  /// radius R (centre (0, −R, 0)), rays going down at up to 60° from the
  /// vertical. c = |p|² − R² = 2Rh + h² cancels in the naive formula; the
  /// stable one gets it from `CameraRelative`. Integer coordinates keep the
  /// reference exact.
  func checkHugeSphereFromClose<T: RayScalar>(
    _: T.Type, radius: T, stableBudget: Double, base: UInt64
  ) -> (stable: Double, naive: Double) {
    var worst = (stable: 0.0, naive: 0.0)
    forEachSeed(1000, base: base) { generator, seed in
      let height = T(Int.random(in: 1...100, using: &generator))
      let sphere = Sphere<T>(center: Vector3(0, -radius, 0), radius: radius)
      let theta = Double.random(in: 0...(Double.pi / 3), using: &generator)
      let phi = Double.random(in: 0...(2 * Double.pi), using: &generator)
      let direction = Vector3<T>(
        Vector3(
          Double.sin(theta) * Double.cos(phi), -Double.cos(theta),
          Double.sin(theta) * Double.sin(phi)))
      let ray = Ray(origin: Vector3(0, height, 0), direction: direction)
      guard let want = referenceIntersect(ray, sphere),
        let stable = sphere.intersect(
          ray, after: 0, before: .infinity, method: .stable)
      else {
        XCTFail("seed \(seed): the reference and the stable method must hit")
        return
      }
      worst.stable = max(
        worst.stable,
        assertRelativeError(
          stable.t, want.t, ulps: stableBudget, "stable, seed \(seed)"))
      let naive = sphere.intersect(
        ray, after: 0, before: .infinity, method: .naive)
      worst.naive = max(
        worst.naive,
        naive.map { relativeErrorInUlps($0.t, want.t) } ?? .infinity)
      // Here the normal is well conditioned (L ≪ R): compare it too.
      // Measured worst 1 ulp of the largest component; budget 4.
      assertRelativeError(
        stable.normal, want.normal, ulps: 4, "planet normal, seed \(seed)")
    }
    print("\(T.self) huge sphere r = \(radius) worst: \(worst)")
    return worst
  }

  func testPrecision_HugeSphereFromClose_Float() {
    // Measured worst of t: stable 1.4 ulps at R = 1e6 and 1.6 at R = 1e9
    // (the largest the exact reference allows); naive 2.9e5 and 1.5e16 ulps.
    for (radius, base): (Float, UInt64) in [
      (1e6, 0x5EED_0007), (1e9, 0x5EED_0017),
    ] {
      let worst = checkHugeSphereFromClose(
        Float.self, radius: radius, stableBudget: 4, base: base)
      XCTAssertGreaterThan(
        worst.naive, 1e3,
        "the naive formula was expected to fail at R = \(radius)")
    }
  }

  func testPrecision_HugeSphereFromClose_Double() {
    // Measured worst of t: stable 1.5 ulps at R = 1e9; naive 1.8e8 ulps.
    let worst = checkHugeSphereFromClose(
      Double.self, radius: 1e9, stableBudget: 4, base: 0x5EED_0008)
    XCTAssertGreaterThan(
      worst.naive, 1e3, "the naive formula was expected to fail at R = 1e9")
  }
}
