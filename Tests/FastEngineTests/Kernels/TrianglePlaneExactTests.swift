import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// A triangle much larger than its distance from the ray's origin takes t
/// from its plane (`TrianglePlane`); every other keeps the watertight
/// test's t.
final class TrianglePlaneExactTests: XCTestCase {
  /// A ground triangle 2·10⁶ across, y = 0.
  let ground = Triangle<Double>(
    Vector3(-1e6, 0, 1e6), Vector3(1e6, 0, 1e6), Vector3(0, 0, -1e6))

  /// Seen from one unit above: the plane's t is k / d.y, one rounding
  /// (k = −1 and n·d = d.y exactly for the axis-aligned normal), where the
  /// watertight t (the naive method) is off by thousands of ulps.
  func testIntersect_GroundTriangleSeenFromOneUnitAbove() throws {
    let origin = Vector3<Double>(0.25, 1, 0.5)
    for (x, z) in [(0.3, -1.0), (-0.7, -0.2), (0.05, 0.9)] {
      let d = Vector3(x, -0.2, z).normalized()
      let ray = Ray(origin: origin, direction: d)
      let stable = try XCTUnwrap(
        ground.intersect(ray, after: 0, before: .infinity, method: .stable))
      XCTAssertEqual(stable.t, -1 / d.y, "direction \(d)")
      let naive = try XCTUnwrap(
        ground.intersect(ray, after: 0, before: .infinity, method: .naive))
      XCTAssertGreaterThan(
        (naive.t - stable.t).magnitude / stable.t, 1000 * Double.ulpOfOne,
        "the watertight t is not the plane's here")
    }
  }

  /// The interval still filters: behind the origin, or beyond tMax, misses.
  func testIntersect_GroundTriangleInterval() {
    let ray = Ray<Double>(
      origin: Vector3(0, 1, 0), direction: Vector3(0, -1, 0))
    XCTAssertNil(
      ground.intersect(ray, after: 0, before: 0.5, method: .stable))
    let up = Ray<Double>(origin: Vector3(0, 1, 0), direction: Vector3(0, 1, 0))
    XCTAssertNil(
      ground.intersect(up, after: 0, before: .infinity, method: .stable))
  }

  /// Only triangles reaching beyond `reach` times their plane's distance
  /// take the plane.
  func testMake_OnlyLargeTriangles() throws {
    func plane(_ triangle: Triangle<Double>, from origin: Vector3<Double>)
      -> (normal: Vector3<Double>, distance: Double)?
    {
      let seen = Triangle(
        triangle.v0 - origin, triangle.v1 - origin, triangle.v2 - origin)
      guard let normal = seen.geometricNormal else { return nil }
      return TrianglePlane.make(
        relative: (seen.v0, seen.v1, seen.v2), normal: normal,
        v0: triangle.v0, origin: origin)
    }
    let from = Vector3<Double>(0, 1, 0)
    XCTAssertEqual(try XCTUnwrap(plane(ground, from: from)).distance, -1)
    let small = Triangle<Double>(
      Vector3(-1, 0, 1), Vector3(1, 0, 1), Vector3(0, 0, -1))
    XCTAssertNil(plane(small, from: from))
  }
}
