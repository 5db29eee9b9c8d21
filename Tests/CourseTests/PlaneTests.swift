import Course
import Geometry
import SceneDescription
import XCTest


/// The course's plane: t = (d − n·o) / (n·d), both sides, parallel rays.
final class PlaneTests: XCTestCase {
  /// The floor y = −1.
  let floor = Plane(normal: Vector3(0, 1, 0), offset: -1, materialIndex: 2)

  func testIntersect_FromAbove() throws {
    let found = try XCTUnwrap(
      floor.intersect(
        Ray(origin: Vector3(0, 3, 0), direction: Vector3(0, -2, 0)), after: 0,
        before: .infinity))
    XCTAssertEqual(found.t, 2, "4 units down at 2 units per t")
    XCTAssertEqual(found.normal, Vector3(0, 1, 0))
    XCTAssertEqual(found.materialIndex, 2)
  }

  func testIntersect_FromBelow_KeepsItsNormal() throws {
    let found = try XCTUnwrap(
      floor.intersect(
        Ray(origin: Vector3(0, -5, 0), direction: Vector3(0, 1, 0)), after: 0,
        before: .infinity))
    XCTAssertEqual(found.t, 4)
    XCTAssertEqual(found.normal, Vector3(0, 1, 0))
  }

  func testIntersect_Misses() {
    let above = Vector3<Double>(0, 3, 0)
    XCTAssertNil(
      floor.intersect(
        Ray(origin: above, direction: Vector3(1, 0, 0)), after: 0,
        before: .infinity), "parallel")
    XCTAssertNil(
      floor.intersect(
        Ray(origin: above, direction: Vector3(0, 1, 0)), after: 0,
        before: .infinity), "facing away")
    XCTAssertNil(
      floor.intersect(
        Ray(origin: above, direction: Vector3(0, -1, 0)), after: 0, before: 4),
      "beyond tMax")
  }

  /// A tilted plane hit at a grazing angle: t is the exact distance to
  /// within 4 ulps (n·o and n·d are each a few roundings).
  func testIntersect_Tilted() throws {
    let normal = Vector3<Double>(1, 1, 0).normalized()
    let plane = Plane(normal: normal, offset: 0)
    let found = try XCTUnwrap(
      plane.intersect(
        Ray(origin: Vector3(1, 1, 0), direction: Vector3(-1, 0, 0)), after: 0,
        before: .infinity))
    XCTAssertEqual(found.t, 2, accuracy: 4 * 2 * .ulpOfOne)
  }
}
