import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

/// DoubleDouble's raw significand, a 128-bit unsigned integer, against the
/// standard library's UInt128 where that exists.
final class DoubleDoubleSignificandTests: XCTestCase {
  /// DoubleDoubleSignificand against the standard library's UInt128 (macOS
  /// 15 and Linux): +, −, full-width ×, ÷ and % (the bit-serial path and the
  /// fast ones), shifts, bit counts and words, on random operands of random
  /// widths.
  func testArithmetic_AgainstUInt128() throws {
    guard #available(macOS 15.0, *) else {
      throw XCTSkip("UInt128 needs macOS 15; Linux always has it")
    }
    typealias S = DoubleDoubleSignificand
    func wide(_ x: S) -> UInt128 { UInt128(x.high) << 64 | UInt128(x.low) }
    func randomOperand(_ generator: inout SplitMix64) -> S {
      let bits = Int.random(in: 1...128, using: &generator)
      let value = S(
        high: generator.next(), low: generator.next())
      return value.shiftedRight(128 - bits)
    }
    forEachSeed(2_000, base: 0xDD00_0040) { generator, seed in
      let a = randomOperand(&generator)
      let b = randomOperand(&generator)
      let (x, y) = (wide(a), wide(b))
      XCTAssertEqual(
        wide(a.addingReportingOverflow(b).partialValue), x &+ y, "seed \(seed)")
      XCTAssertEqual(
        a.addingReportingOverflow(b).overflow,
        x.addingReportingOverflow(y).overflow, "seed \(seed)")
      XCTAssertEqual(wide(a &- b), x &- y, "seed \(seed)")
      let product = a.multipliedFullWidth(by: b)
      let expected = x.multipliedFullWidth(by: y)
      XCTAssertEqual(wide(product.high), expected.high, "seed \(seed)")
      XCTAssertEqual(wide(product.low), expected.low, "seed \(seed)")
      if b != 0 {
        XCTAssertEqual(wide(a / b), x / y, "seed \(seed)")
        XCTAssertEqual(wide(a % b), x % y, "seed \(seed)")
      }
      let shift = Int.random(in: 0...130, using: &generator)
      XCTAssertEqual(wide(a << shift), x << shift, "seed \(seed)")
      XCTAssertEqual(wide(a >> shift), x >> shift, "seed \(seed)")
      XCTAssertEqual(a < b, x < y, "seed \(seed)")
      XCTAssertEqual(a.leadingZeroBitCount, x.leadingZeroBitCount)
      XCTAssertEqual(a.trailingZeroBitCount, x.trailingZeroBitCount)
      XCTAssertEqual(a.nonzeroBitCount, x.nonzeroBitCount)
      XCTAssertEqual(Array(a.words), Array(x.words), "seed \(seed)")
      XCTAssertEqual(UInt128(a), x, "seed \(seed): generic conversion")
      XCTAssertEqual(S(x), a, "seed \(seed): generic conversion")
      XCTAssertEqual(a.description, x.description, "seed \(seed)")
    }
  }
}
