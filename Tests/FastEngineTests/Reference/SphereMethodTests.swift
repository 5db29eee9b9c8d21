import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

final class SphereMethodTests: XCTestCase {
  // MARK: - Geometry, both methods

  /// Sphere at (0, 0, −10) of radius 2, ray from the origin down −z: roots 8
  /// and 12. Every intermediate value of both methods is a small integer, so
  /// both must give exactly 8 and the normal (0, 0, 1).
  func checkTwoRoots<T: RayScalar>(_: T.Type) {
    let sphere = Sphere<T>(
      center: Vector3(0, 0, -10), radius: 2, materialIndex: 3)
    let ray = Ray<T>(origin: .zero, direction: Vector3(0, 0, -1))
    for method in IntersectionMethod.allCases {
      let hit = sphere.intersect(
        ray, after: 0, before: .infinity, method: method)
      XCTAssertEqual(hit?.t, 8, "\(T.self) \(method): the nearer root")
      XCTAssertEqual(hit?.normal, Vector3(0, 0, 1), "\(T.self) \(method)")
      XCTAssertEqual(hit?.materialIndex, 3, "\(T.self) \(method)")
    }
    // The protocol entry point is the stable method.
    XCTAssertEqual(sphere.intersect(ray, after: 0, before: .infinity)?.t, 8)
  }

  func testIntersect_TwoRoots_Float() { checkTwoRoots(Float.self) }
  func testIntersect_TwoRoots_Double() { checkTwoRoots(Double.self) }

  /// A ray at exactly distance r from the centre: the discriminant is zero
  /// and the double root t = 10 is a hit. r is a power of two so that r² and
  /// every other intermediate value is exact; the tangent normal is +x.
  func checkTangent<T: RayScalar>(_: T.Type) {
    for radius: T in [0.5, 4, 1024] {
      let sphere = Sphere<T>(center: .zero, radius: radius)
      let ray = Ray<T>(
        origin: Vector3(radius, 0, -10), direction: Vector3(0, 0, 1))
      for method in IntersectionMethod.allCases {
        let hit = sphere.intersect(
          ray, after: 0, before: .infinity, method: method)
        XCTAssertEqual(hit?.t, 10, "\(T.self) \(method) r = \(radius)")
        XCTAssertEqual(
          hit?.normal, Vector3(1, 0, 0), "\(T.self) \(method) r = \(radius)")
      }
    }
  }

  func testIntersect_TangentRay_Float() { checkTangent(Float.self) }
  func testIntersect_TangentRay_Double() { checkTangent(Double.self) }

  /// One ulp outside the tangent the stable method misses, one ulp inside it
  /// hits: it measures the distance to the line exactly here (l = (−x, 0, 0)
  /// has no rounding), so the silhouette is sharp to the last bit.
  func checkJustOutsideAndInsideTangent<T: RayScalar>(_: T.Type) {
    let radius: T = 4
    let sphere = Sphere<T>(center: .zero, radius: radius)
    let outside = Ray<T>(
      origin: Vector3(radius.nextUp, 0, -10), direction: Vector3(0, 0, 1))
    XCTAssertNil(
      sphere.intersect(outside, after: 0, before: .infinity, method: .stable),
      "\(T.self): one ulp outside the silhouette")
    let inside = Ray<T>(
      origin: Vector3(radius.nextDown, 0, -10), direction: Vector3(0, 0, 1))
    let hit = sphere.intersect(
      inside, after: 0, before: .infinity, method: .stable)
    XCTAssertNotNil(hit, "\(T.self): one ulp inside the silhouette")
    if let hit, let want = referenceIntersect(inside, sphere) {
      // t = 10 − √(r² − x²) with x one ulp below r. r² − |l|² is exact
      // here, so only c, q and the quotient round: budget 4 ulps.
      assertRelativeError(hit.t, want.t, ulps: 4, "three roundings")
    }
  }

  func testIntersect_JustOutsideAndInsideTangent_Float() {
    checkJustOutsideAndInsideTangent(Float.self)
  }
  func testIntersect_JustOutsideAndInsideTangent_Double() {
    checkJustOutsideAndInsideTangent(Double.self)
  }

  func checkMiss<T: RayScalar>(_: T.Type) {
    let sphere = Sphere<T>(center: Vector3(0, 0, -10), radius: 2)
    let rays = [
      // Passes 3 above the centre.
      Ray<T>(origin: Vector3(0, 3, 0), direction: Vector3(0, 0, -1)),
      // Points away.
      Ray<T>(origin: .zero, direction: Vector3(1, 0, 0)),
      // Oblique, closest approach √50 > 2.
      Ray<T>(origin: Vector3(-10, 0, 0), direction: Vector3(1, 0, 1)),
    ]
    for ray in rays {
      for method in IntersectionMethod.allCases {
        XCTAssertNil(
          sphere.intersect(ray, after: 0, before: .infinity, method: method),
          "\(T.self) \(method) \(ray)")
      }
    }
  }

  func testIntersect_Miss_Float() { checkMiss(Float.self) }
  func testIntersect_Miss_Double() { checkMiss(Double.self) }

  /// Both roots (−12 and −8) behind the origin: no hit.
  func checkBothRootsBehind<T: RayScalar>(_: T.Type) {
    let sphere = Sphere<T>(center: Vector3(0, 0, 10), radius: 2)
    let ray = Ray<T>(origin: .zero, direction: Vector3(0, 0, -1))
    for method in IntersectionMethod.allCases {
      XCTAssertNil(
        sphere.intersect(ray, after: 0, before: .infinity, method: method),
        "\(T.self) \(method)")
    }
  }

  func testIntersect_BothRootsBehind_Float() {
    checkBothRootsBehind(Float.self)
  }
  func testIntersect_BothRootsBehind_Double() {
    checkBothRootsBehind(Double.self)
  }

  /// From the centre the near root is −r: the hit is the far side, t = r,
  /// with the normal pointing outward (along the ray), not back at the eye.
  /// From an off-centre inside point the far root is checked against the
  /// reference.
  func checkOriginInside<T: RayScalar>(_: T.Type) {
    let sphere = Sphere<T>(center: Vector3(0, 0, -10), radius: 2)
    let fromCentre = Ray<T>(
      origin: Vector3(0, 0, -10), direction: Vector3(0, 0, -1))
    let offCentre = Ray<T>(
      origin: Vector3(0.5, -0.25, -9), direction: Vector3(0.3, 0.2, -1))
    for method in IntersectionMethod.allCases {
      let hit = sphere.intersect(
        fromCentre, after: 0, before: .infinity, method: method)
      XCTAssertEqual(hit?.t, 2, "\(T.self) \(method): exact, small integers")
      XCTAssertEqual(hit?.normal, Vector3(0, 0, -1), "\(T.self) \(method)")

      let inside = sphere.intersect(
        offCentre, after: 0, before: .infinity, method: method)
      guard let inside, let want = referenceIntersect(offCentre, sphere) else {
        XCTFail("\(T.self) \(method): a ray from inside must hit")
        continue
      }
      // Well conditioned (the origin is far from the surface): a handful
      // of roundings in either method.
      assertRelativeError(inside.t, want.t, ulps: 8, "\(method), from inside")
      let centreOffset = offCentre.point(at: inside.t) - sphere.center
      XCTAssertGreaterThan(
        inside.normal.dot(centreOffset), 0, "\(T.self) \(method): outward")
    }
  }

  func testIntersect_OriginInside_Float() { checkOriginInside(Float.self) }
  func testIntersect_OriginInside_Double() { checkOriginInside(Double.self) }

  /// From a point on the surface with tMin = 0, the root t = 0 is excluded:
  /// a ray entering the sphere hits the far side; one leaving it misses.
  func checkOriginOnSurface<T: RayScalar>(_: T.Type) {
    let sphere = Sphere<T>(center: Vector3(0, 0, -10), radius: 2)
    let entering = Ray<T>(
      origin: Vector3(0, 0, -8), direction: Vector3(0, 0, -1))
    let leaving = Ray<T>(origin: Vector3(0, 0, -8), direction: Vector3(0, 0, 1))
    for method in IntersectionMethod.allCases {
      let hit = sphere.intersect(
        entering, after: 0, before: .infinity, method: method)
      XCTAssertEqual(hit?.t, 4, "\(T.self) \(method): the far side, exactly")
      XCTAssertEqual(hit?.normal, Vector3(0, 0, -1), "\(T.self) \(method)")
      XCTAssertNil(
        sphere.intersect(leaving, after: 0, before: .infinity, method: method),
        "\(T.self) \(method): roots 0 and −4")
    }
  }

  func testIntersect_OriginOnSurface_Float() {
    checkOriginOnSurface(Float.self)
  }
  func testIntersect_OriginOnSurface_Double() {
    checkOriginOnSurface(Double.self)
  }

  /// Roots 8 and 12; the interval is open at both ends.
  func checkInterval<T: RayScalar>(_: T.Type) {
    let sphere = Sphere<T>(center: Vector3(0, 0, -10), radius: 2)
    let ray = Ray<T>(origin: .zero, direction: Vector3(0, 0, -1))
    let cases: [(tMin: T, tMax: T, want: T?)] = [
      (9, .infinity, 12),  // tMin between the roots: the far root
      (8, .infinity, 12),  // t = tMin is excluded
      (12, .infinity, nil),
      (13, .infinity, nil),  // beyond both
      (0, 10, 8),
      (0, 8, nil),  // t = tMax is excluded
      (0, 7.5, nil),  // both beyond tMax
      (8.5, 11.5, nil),  // between the roots
      (-100, .infinity, 8),
    ]
    for method in IntersectionMethod.allCases {
      for (tMin, tMax, want) in cases {
        XCTAssertEqual(
          sphere.intersect(ray, after: tMin, before: tMax, method: method)?.t,
          want,
          "\(T.self) \(method) (\(tMin), \(tMax))")
      }
    }
  }

  func testIntersect_Interval_Float() { checkInterval(Float.self) }
  func testIntersect_Interval_Double() { checkInterval(Double.self) }

  /// t is measured in multiples of |d|: d = (0, 0, −4) reaches the sphere at
  /// t = 8/4 = 2 (exact, powers of two); d = (0, 0, −3) at 8/3, one rounding
  /// plus the method's own.
  func checkNonUnitDirection<T: RayScalar>(_: T.Type) {
    let sphere = Sphere<T>(center: Vector3(0, 0, -10), radius: 2)
    let four = Ray<T>(origin: .zero, direction: Vector3(0, 0, -4))
    let three = Ray<T>(origin: .zero, direction: Vector3(0, 0, -3))
    for method in IntersectionMethod.allCases {
      let hit = sphere.intersect(
        four, after: 0, before: .infinity, method: method)
      XCTAssertEqual(hit?.t, 2, "\(T.self) \(method)")
      XCTAssertEqual(hit?.normal, Vector3(0, 0, 1), "\(T.self) \(method)")
      guard
        let third = sphere.intersect(
          three, after: 0, before: .infinity, method: method)
      else {
        XCTFail("\(T.self) \(method): d = (0, 0, −3) must hit")
        continue
      }
      // 8/3 rounded once, then the method's own few roundings.
      assertRelativeError(
        third.t, 8 / 3 as ReferenceScalar, ulps: 2, "\(method)")
    }
  }

  func testIntersect_NonUnitDirection_Float() {
    checkNonUnitDirection(Float.self)
  }
  func testIntersect_NonUnitDirection_Double() {
    checkNonUnitDirection(Double.self)
  }

  /// Random spheres off the origin at moderate scales (distance/radius up
  /// to 100), rays aimed inside 0.9 of the radius (away from the
  /// silhouette, where t is ill-conditioned), checked against the reference.
  func checkOffOriginRandom<T: RayScalar>(_: T.Type, base: UInt64) {
    var worst = (stable: 0.0, naive: 0.0, normal: 0.0)
    forEachSeed(500, base: base) { generator, seed in
      let radius: T = generator.logUniform(0.1, 10)
      let centre = generator.unitVector(T.self) * generator.logUniform(0.1, 100)
      let origin =
        centre
        + generator.unitVector(T.self) * radius * generator.logUniform(1.5, 100)
      let aim =
        centre
        + generator.unitVector(T.self) * radius
        * generator.uniform(0...0.9, as: T.self)
      let ray = Ray(origin: origin, direction: aim - origin)
      let sphere = Sphere(center: centre, radius: radius)
      guard let want = referenceIntersect(ray, sphere) else {
        XCTFail("seed \(seed): the reference must hit")
        return
      }
      guard
        let stable = sphere.intersect(
          ray, after: 0, before: .infinity, method: .stable),
        let naive = sphere.intersect(
          ray, after: 0, before: .infinity, method: .naive)
      else {
        XCTFail("seed \(seed): both methods must hit")
        return
      }
      // Measured worst over these 500 cases: 1.6 ulps in Float and in
      // Double. Budget 4: the relative errors of c, q and a quotient.
      let stableError = assertRelativeError(
        stable.t, want.t, ulps: 4, "stable, seed \(seed)")
      // The naive discriminant loses up to (L/r)²·ε here; measured worst
      // 114 ulps (Float), 109 (Double); only a sanity bound of 2^12 ulps is
      // asserted.
      let naiveError = assertRelativeError(
        naive.t, want.t, ulps: 4096, "naive, moderate scales, seed \(seed)")
      // The normal comes from the closest-approach vector l, found by
      // cancelling |p| = |centre − origin| down to at most r: its absolute
      // error is about ε|p|, so the normal's is about (|p|/r)·ε, and more
      // by 1/cos(incidence) ≤ 2.3 for aims within 0.9 r. Budget
      // 4·(1 + |p|/r) ulps of the largest component; measured worst
      // 1.0·(1 + |p|/r) in Float, 1.24·(1 + |p|/r) in Double.
      let conditioning = 1 + Double((centre - origin).length / radius)
      let normalError = assertRelativeError(
        stable.normal, want.normal, ulps: 4 * conditioning,
        "stable normal, |p|/r = \(conditioning - 1), seed \(seed)")
      worst.stable = max(worst.stable, stableError)
      worst.naive = max(worst.naive, naiveError)
      worst.normal = max(worst.normal, normalError / conditioning)
    }
    print("\(T.self) off-origin worst: \(worst)")
  }

  func testIntersect_OffOriginRandom_Float() {
    checkOffOriginRandom(Float.self, base: 0x5EED_0001)
  }
  func testIntersect_OffOriginRandom_Double() {
    checkOffOriginRandom(Double.self, base: 0x5EED_0002)
  }

  // MARK: - Normals

  /// Unit length and outward, on spheres off the origin and from inside;
  /// t from inside against the reference.
  func checkNormals<T: RayScalar>(_: T.Type, base: UInt64) {
    forEachSeed(500, base: base) { generator, seed in
      let radius: T = generator.logUniform(1e-3, 1e3)
      let centre =
        generator.unitVector(T.self) * generator.logUniform(1e-3, 1e3)
      let sphere = Sphere(center: centre, radius: radius)
      // Half the rays start outside, half inside.
      let inside = Bool.random(using: &generator)
      let distance: T =
        inside
        ? generator.uniform(0...0.9, as: T.self) : generator.logUniform(1.5, 50)
      let origin = centre + generator.unitVector(T.self) * radius * distance
      let direction =
        inside
        ? generator.unitVector(T.self)
        : (centre + generator.unitVector(T.self) * radius * 0.9 - origin)
      let ray = Ray(origin: origin, direction: direction)
      for method in IntersectionMethod.allCases {
        guard
          let hit = sphere.intersect(
            ray, after: 0, before: .infinity, method: method)
        else {
          XCTFail("seed \(seed) \(method): must hit")
          continue
        }
        // |n| − 1: normalisation rounds each component and the square
        // root; measured worst 1 ulp, budget 2.
        let lengthError =
          (Double(hit.normal.length) - 1).magnitude
          / Double(T.ulpOfOne)
        XCTAssertLessThanOrEqual(
          lengthError, 2, "seed \(seed) \(method): |n| − 1 in ulps")
        let fromCentre = ray.point(at: hit.t) - centre
        XCTAssertGreaterThan(
          hit.normal.dot(fromCentre), 0,
          "seed \(seed) \(method) inside: \(inside): outward")
        // From inside, rays leave in every direction (p·d of either
        // sign): the far root must be as accurate as the near one was
        // above. Measured worst 1.6 ulps; budget 4.
        if method == .stable, let want = referenceIntersect(ray, sphere) {
          assertRelativeError(
            hit.t, want.t, ulps: 4, "seed \(seed) stable, inside: \(inside)")
        }
      }
    }
  }

  func testNormal_UnitAndOutward_Float() {
    checkNormals(Float.self, base: 0x5EED_0003)
  }
  func testNormal_UnitAndOutward_Double() {
    checkNormals(Double.self, base: 0x5EED_0004)
  }
}
