import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

final class RayTests: XCTestCase {
  /// origin + t·direction, with t in multiples of |direction|.
  func checkPoint<T: RayScalar>(_: T.Type) {
    let ray = Ray<T>(origin: Vector3(1, 2, 3), direction: Vector3(0, -2, 0.5))
    XCTAssertEqual(ray.point(at: 0), ray.origin)
    XCTAssertEqual(ray.point(at: 2), Vector3(1, -2, 4))
    XCTAssertEqual(ray.point(at: -1), Vector3(1, 4, 2.5))
  }

  func testPoint_Float() { checkPoint(Float.self) }
  func testPoint_Double() { checkPoint(Double.self) }
}
