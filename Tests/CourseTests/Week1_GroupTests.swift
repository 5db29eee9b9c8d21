import Course
import Geometry
import SceneDescription
import XCTest

/// Week 1, camera and planes: a group (`Group.intersect`), the nearest hit
/// of all its objects in (tMin, tMax), a tie going to the object listed
/// first. Made of planes, this week's shape.
final class Week1_GroupTests: XCTestCase {
  /// The plane z = −depth facing the eye at the origin, hit at t = depth
  /// by the ray down −z.
  func wall(_ depth: Double, material: Int) -> Plane {
    Plane(normal: Vector3(0, 0, 1), offset: -depth, materialIndex: material)
  }

  let down = Ray<Double>(origin: .zero, direction: Vector3(0, 0, -1))

  func testIntersect_TheNearest_WhereverItIsListed() throws {
    for order in [[5.0, 1, 3], [1, 3, 5], [3, 5, 1]] {
      let group = Group(order.map { wall($0, material: Int($0)) })
      let found = try XCTUnwrap(
        group.intersect(down, after: 0, before: .infinity), "\(order)")
      XCTAssertEqual(found.t, 1, "\(order)")
      XCTAssertEqual(found.materialIndex, 1, "\(order)")
    }
  }

  /// Two objects hit at the same t: the one listed first.
  func testIntersect_Tie_TheFirstListed() throws {
    let first = try XCTUnwrap(
      Group([wall(2, material: 7), wall(2, material: 8)])
        .intersect(down, after: 0, before: .infinity))
    XCTAssertEqual(first.materialIndex, 7)
    let swapped = try XCTUnwrap(
      Group([wall(2, material: 8), wall(2, material: 7)])
        .intersect(down, after: 0, before: .infinity))
    XCTAssertEqual(swapped.materialIndex, 8)
  }

  /// The nearest in (tMin, tMax): walls at 1, 3 and 5.
  func testIntersect_Interval() throws {
    let group = Group([5.0, 1, 3].map { wall($0, material: Int($0)) })
    let after = try XCTUnwrap(group.intersect(down, after: 1, before: 9))
    XCTAssertEqual(after.materialIndex, 3, "the nearest after tMin")
    XCTAssertNil(group.intersect(down, after: 0, before: 1), "open at tMax")
    XCTAssertNil(group.intersect(down, after: 5, before: 9), "none after")
  }

  func testIntersect_Misses() {
    XCTAssertNil(Group([]).intersect(down, after: 0, before: .infinity))
    let behind = Group([wall(-2, material: 1), wall(-4, material: 2)])
    XCTAssertNil(behind.intersect(down, after: 0, before: .infinity))
  }

  /// A group in a group is one more object, hit as its nearest.
  func testIntersect_NestedGroups() throws {
    let inner = Group([wall(4, material: 4), wall(2, material: 2)])
    let outer = Group([wall(3, material: 3), inner])
    let found = try XCTUnwrap(outer.intersect(down, after: 0, before: 9))
    XCTAssertEqual(found.materialIndex, 2)
  }
}
