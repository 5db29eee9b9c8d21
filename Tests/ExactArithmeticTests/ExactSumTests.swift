import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

/// `ExactSum` against `ExactDyadic` (schoolbook integers, no
/// floating-point arithmetic): sums of products that cancel to any depth.
final class ExactSumTests: XCTestCase {
  func testCancellingSumsOfProducts() {
    var generator = SplitMix64(seed: 5)
    func value() -> Double {
      let mantissa = Double(generator.next() % (1 << 53)) / Double(1 << 53)
      let exponent = Int(generator.next() % 120) - 60
      return Double(sign: generator.next() % 2 == 0 ? .plus : .minus,
        exponent: exponent, significand: 1 + mantissa)
    }
    for trial in 0..<500 {
      var sum = ExactSum()
      var exact = ExactDyadic.zero
      var pairs: [(Double, Double)] = []
      for _ in 0..<(1 + trial % 8) { pairs.append((value(), value())) }
      // Each product again with its sign flipped, but one factor nudged
      // by an ulp: the sum cancels to the nudges' few bits.
      for (a, b) in pairs where trial % 2 == 0 {
        pairs.append((-a.nextUp, b))
      }
      for (a, b) in pairs {
        sum.add(a, times: b)
        exact = exact + ExactDyadic(a) * ExactDyadic(b)
      }
      let (hi, lo) = sum.pair
      let error = exact - ExactDyadic(hi) - ExactDyadic(lo)
      if exact.isZero {
        XCTAssertTrue(sum.isZero && hi == 0 && lo == 0, "trial \(trial)")
        continue
      }
      // hi + lo within 2⁻¹⁰⁴ of the exact sum, relative.
      let relative =
        error.isZero
        ? 0
        : (ScaledDoubleDouble(error) / ScaledDoubleDouble(exact)).value.hi
          .magnitude
      XCTAssertLessThanOrEqual(relative, 0x1p-104, "trial \(trial)")
      XCTAssertLessThanOrEqual(abs(lo), hi.ulp, "trial \(trial)")
    }
  }
}
