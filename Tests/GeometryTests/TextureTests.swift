import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

/// The nearest-texel lookup: u across from the left, v up from the bottom,
/// 1 on the last texel, outside [0, 1] clamped.
final class TextureTests: XCTestCase {
  /// A 3×2 image whose texels are all different: red = column, green =
  /// row from the top.
  let texture = Texture(
    image: Image8(
      width: 3, height: 2,
      bytes: (0..<2).flatMap { row in
        (0..<3).flatMap { column in [UInt8(column), UInt8(row), 7] }
      }))

  func texel(_ u: Double, _ v: Double) -> (column: Int, row: Int) {
    let color = texture.color(at: TextureCoordinate(u, v))
    return (Int((color.x * 255).rounded()), Int((color.y * 255).rounded()))
  }

  func testLookup_Corners() {
    XCTAssertTrue(texel(0, 0) == (0, 1), "u 0, v 0: left column, bottom row")
    XCTAssertTrue(texel(0, 1) == (0, 0), "v 1 is the top row")
    XCTAssertTrue(texel(1, 0) == (2, 1), "u 1: the last column, not beyond")
    XCTAssertTrue(texel(1, 1) == (2, 0))
  }

  /// Texel boundaries: ⌊u·W⌋ and ⌊(1 − v)·H⌋.
  func testLookup_Boundaries() {
    XCTAssertTrue(texel(0.33, 0.6) == (0, 0))
    XCTAssertTrue(texel(1.0 / 3 + 1e-9, 0.49) == (1, 1))
    XCTAssertTrue(texel(0.67, 0.5) == (2, 1), "(1 − 0.5)·2 = 1: row 1")
  }

  func testLookup_OutsideClamps() {
    XCTAssertTrue(texel(-3, 7) == (0, 0))
    XCTAssertTrue(texel(5, -2) == (2, 1))
    XCTAssertTrue(texel(.nan, .nan) == (0, 0))
    XCTAssertTrue(texel(.infinity, -.infinity) == (2, 1))
  }

  /// Colours are the bytes over 255, exactly as Float or Double divide.
  func testColor_Scale() {
    let color: RGB<Float> = texture.color(at: TextureCoordinate(0.9, 0))
    XCTAssertEqual(
      color, Vector3(Float(2) / 255, Float(1) / 255, Float(7) / 255))
  }
}
