import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `ImageStyle.quantize` takes a fast path through Double for Float and
/// Double; it must agree with truncation (course) and rounding half away
/// from zero (mit) of v·255 computed in the value's own type.
final class QuantizeTests: XCTestCase {
  func expected<S: RayScalar>(_ value: S, _ style: ImageStyle) -> UInt8 {
    guard value > 0 else { return 0 }
    guard value < 1 else { return 255 }
    // In the reference precision (wider than Double where the platform
    // has it): v·255 in the value's own type, then rounded once more.
    let scaled = ReferenceScalar(value * 255)
    let whole =
      style == .course ? scaled.rounded(.towardZero) : scaled.rounded()
    return UInt8(whole)
  }

  func check<S: RayScalar>(_: S.Type) {
    var values: [S] = [
      0, 1, -0.0, -1, 2, .infinity, -.infinity, .nan, .leastNonzeroMagnitude,
    ]
    // Exactly k/255 and (k + 1/2)/255, where truncation and rounding
    // change, and their neighbours.
    for k in 0...255 {
      for fraction in [S(0), S(0.5)] {
        let value = (S(k) + fraction) / 255
        values += [value, value.nextUp, value.nextDown]
      }
    }
    var generator = SplitMix64(seed: 9)
    for _ in 0..<10_000 {
      values.append(S(Double.random(in: 0..<1, using: &generator)))
    }
    for style in ImageStyle.allCases {
      for value in values {
        XCTAssertEqual(
          style.quantize(value), expected(value, style),
          "\(S.self) \(style) \(value)")
      }
    }
  }

  func testFloat() { check(Float.self) }
  func testDouble() { check(Double.self) }
  #if arch(x86_64) || arch(i386)
    func testFloat80() { check(Float80.self) }
  #endif
}
