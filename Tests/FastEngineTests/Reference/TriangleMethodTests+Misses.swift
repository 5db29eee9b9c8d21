import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension TriangleMethodTests {
  // MARK: - Misses

  /// Rays parallel to the plane miss, above it or lying in it; a ray
  /// pointing away misses; zero and NaN directions miss without trapping.
  func checkParallelAndInvalid<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let rays: [(String, Ray<T>)] = [
      (
        "above, along x",
        Ray(origin: Vector3(-1, 0.25, 1), direction: Vector3(1, 0, 0))
      ),
      (
        "below, diagonal",
        Ray(origin: Vector3(-1, -1, -0.5), direction: Vector3(1, 1, 0))
      ),
      (
        "in the plane, along x",
        Ray(origin: Vector3(-1, 0.25, 0), direction: Vector3(1, 0, 0))
      ),
      (
        "in the plane, diagonal",
        Ray(origin: Vector3(-1, -1, 0), direction: Vector3(3, 2, 0))
      ),
      (
        "pointing away",
        Ray(origin: Vector3(0.25, 0.25, 1), direction: Vector3(0, 0, 1))
      ),
      ("zero direction", Ray(origin: Vector3(0.25, 0.25, 1), direction: .zero)),
      (
        "NaN direction",
        Ray(origin: Vector3(0.25, 0.25, 1), direction: Vector3(0, 0, T.nan))
      ),
      (
        "NaN origin",
        Ray(origin: Vector3(T.nan, 0.25, 1), direction: Vector3(0, 0, -1))
      ),
    ]
    for (name, ray) in rays {
      XCTAssertNil(kernel(ray, triangle), "\(T.self) \(name)")
      XCTAssertNil(
        triangle.intersect(ray, after: 0, before: .infinity),
        "\(T.self) \(name)")
    }
  }

  func testIntersect_ParallelAndInvalid_Float() {
    checkParallelAndInvalid(Float.self)
  }
  func testIntersect_ParallelAndInvalid_Double() {
    checkParallelAndInvalid(Double.self)
  }

  /// The back face is hit, with the normal of the winding (+z), not turned
  /// towards the ray; reversing the winding reverses the normal.
  func checkBackFace<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let fromBelow = Ray<T>(
      origin: Vector3(0.25, 0.25, -3), direction: Vector3(0, 0, 1))
    let hit = triangle.intersect(fromBelow, after: 0, before: .infinity)
    XCTAssertEqual(hit?.t, 3, "\(T.self)")
    XCTAssertEqual(
      hit?.normal, Vector3(0, 0, 1), "\(T.self): as wound, not flipped")
    let reversed = Triangle(triangle.v0, triangle.v2, triangle.v1)
    XCTAssertEqual(
      reversed.intersect(fromBelow, after: 0, before: .infinity)?.normal,
      Vector3(0, 0, -1), "\(T.self)")
  }

  func testIntersect_BackFace_Float() { checkBackFace(Float.self) }
  func testIntersect_BackFace_Double() { checkBackFace(Double.self) }

  /// Zero-area triangles miss, however the ray meets them: all three
  /// vertices equal, a repeated vertex, and exactly collinear vertices,
  /// along and across the segment they span.
  func checkDegenerate<T: RayScalar>(_: T.Type) {
    let cases: [(String, Triangle<T>)] = [
      (
        "one point",
        Triangle(Vector3(1, 1, 0), Vector3(1, 1, 0), Vector3(1, 1, 0))
      ),
      (
        "repeated vertex",
        Triangle(Vector3(0, 0, 0), Vector3(0, 0, 0), Vector3(2, 2, 0))
      ),
      (
        "repeated last vertex",
        Triangle(Vector3(0, 0, 0), Vector3(2, 2, 0), Vector3(2, 2, 0))
      ),
      (
        "collinear",
        Triangle(Vector3(0, 0, 0), Vector3(1, 1, 0), Vector3(2, 2, 0))
      ),
      (
        "collinear, oblique",
        Triangle(Vector3(0, 0, 0), Vector3(1, 2, 3), Vector3(4, 8, 12))
      ),
    ]
    for (name, triangle) in cases {
      XCTAssertTrue(triangle.isDegenerate, "\(T.self) \(name)")
      XCTAssertNil(triangle.geometricNormal, "\(T.self) \(name)")
      // Through the middle of the segment, and through an endpoint, from
      // several directions.
      let middle = (triangle.v0 + triangle.v2) * 0.5
      for target in [middle, triangle.v0, triangle.v2] {
        for direction in [
          Vector3<T>(0, 0, -1), Vector3(0.5, -0.25, -1), Vector3(-1, 0.5, 0.25),
        ] {
          let ray = Ray(origin: target - direction * 2, direction: direction)
          XCTAssertNil(
            triangle.intersect(ray, after: 0, before: .infinity),
            "\(T.self) \(name) at \(target) along \(direction)")
        }
      }
    }
    XCTAssertFalse(unitTriangle(T.self).isDegenerate)
    XCTAssertTrue(
      Triangle<T>(Vector3(0, 0, 0), Vector3(T.nan, 0, 0), Vector3(0, 1, 0))
        .isDegenerate)
  }

  func testIntersect_Degenerate_Float() { checkDegenerate(Float.self) }
  func testIntersect_Degenerate_Double() { checkDegenerate(Double.self) }

  /// Only tMin < t < tMax counts: a hit at exactly either end is excluded,
  /// one ulp inside is included, and a triangle behind the origin (t < 0)
  /// is missed with tMin = 0.
  func checkInterval<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let ray = Ray<T>(
      origin: Vector3(0.25, 0.25, 2), direction: Vector3(0, 0, -1))
    XCTAssertNil(triangle.intersect(ray, after: 0, before: 2), "t = tMax")
    XCTAssertEqual(triangle.intersect(ray, after: 0, before: T(2).nextUp)?.t, 2)
    XCTAssertNil(
      triangle.intersect(ray, after: 2, before: .infinity), "t = tMin")
    XCTAssertEqual(
      triangle.intersect(ray, after: T(2).nextDown, before: 3)?.t, 2)
    let behind = Ray<T>(
      origin: Vector3(0.25, 0.25, -2), direction: Vector3(0, 0, -1))
    XCTAssertNil(triangle.intersect(behind, after: 0, before: .infinity))
    XCTAssertEqual(
      triangle.intersect(behind, after: -.infinity, before: 0)?.t, -2,
      "the kernel finds it when the interval allows")
  }

  func testIntersect_Interval_Float() { checkInterval(Float.self) }
  func testIntersect_Interval_Double() { checkInterval(Double.self) }

  /// t is in multiples of the direction's length: scaling the direction by
  /// a power of two divides t exactly and leaves the barycentrics
  /// unchanged; by 3, t/3 within 2 ulps (the rounded 3·d and one more
  /// rounding of the result).
  func checkNonUnitDirections<T: RayScalar>(_: T.Type) {
    let triangle = Triangle<T>(
      Vector3(-1, -1, 5), Vector3(3, 0, 6), Vector3(0, 2, 4))
    let origin = Vector3<T>(0.1, 0.2, -0.3)
    let unit = (Vector3<T>(0.5, 0.4, 5) - origin).normalized()
    guard let reference = kernel(Ray(origin: origin, direction: unit), triangle)
    else {
      return XCTFail("\(T.self): the unit ray misses")
    }
    for scale: T in [4, 0.125, 1024] {
      let hit = kernel(Ray(origin: origin, direction: unit * scale), triangle)
      XCTAssertEqual(hit?.t, reference.t / scale, "\(T.self) × \(scale)")
      XCTAssertEqual(hit?.u, reference.u, "\(T.self) × \(scale)")
      XCTAssertEqual(hit?.w, reference.w, "\(T.self) × \(scale)")
    }
    let tripled = Ray(origin: origin, direction: unit * 3)
    guard let hit = kernel(tripled, triangle),
      let exact = referenceTriangleHit(tripled, triangle)
    else { return XCTFail("\(T.self): the tripled ray misses") }
    assertRelativeError(
      hit.t, exact.t, ulps: 8, "\(T.self): as the interior bound")
    assertRelativeError(
      hit.t * 3, ReferenceScalar(reference.t), ulps: 4,
      "\(T.self): 3·d rounds, t/3 rounds, and each t carries a few ulps")
  }

  func testIntersect_NonUnitDirections_Float() {
    checkNonUnitDirections(Float.self)
  }
  func testIntersect_NonUnitDirections_Double() {
    checkNonUnitDirections(Double.self)
  }
}
