import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

extension DoubleDoubleTests {
  // MARK: - The model

  /// Fields and neighbours agree with the value: the encoding round-trips,
  /// sign·significand·2^exponent is the value, the next value up is ulp
  /// away and back down again, significandWidth counts the bits used.
  func testModel_FieldsAndNeighboursConsistent() {
    forEachSeed(5_000, base: 0xDD00_0030) { generator, seed in
      let x = random(&generator, 0x1p-1000, 0x1p1000)
      let encoded = DD(
        sign: x.sign, exponentBitPattern: x.exponentBitPattern,
        significandBitPattern: x.significandBitPattern)
      XCTAssertEqual(encoded, x, "seed \(seed): encoding")
      XCTAssertEqual(
        DD(sign: x.sign, exponent: x.exponent, significand: x.significand), x,
        "seed \(seed): sign, exponent, significand")
      XCTAssert(
        (1..<2).contains(x.significand), "seed \(seed): \(x.significand)")
      let up = x.nextUp
      assertCanonical(up, "seed \(seed)")
      XCTAssertEqual(up.nextDown, x, "seed \(seed): \(x)")
      XCTAssertGreaterThan(up, x, "seed \(seed)")
      if x > 0 {
        XCTAssertEqual(up - x, x.ulp, "seed \(seed): ulp")
      }
      let lowest = x.lo != 0 ? x.lo : x.hi
      XCTAssertEqual(
        x.significandWidth,
        x.exponent - Int(lowest.exponent) + lowest.significandWidth,
        "seed \(seed)")
      XCTAssertEqual(
        x.binade,
        DD(x.sign == .minus ? -1 : 1)
          * DD(
            Double(sign: .plus, exponent: x.exponent, significand: 1)))
    }
    XCTAssertEqual(DD.ulpOfOne, DD(0x1p-105))
    XCTAssertEqual(DD(1).nextUp, DD(1, 0x1p-105))
    XCTAssertEqual(DD(1).nextDown, DD(1, -0x1p-106))
    XCTAssertEqual(DD.significandBitCount, 105)
    XCTAssertEqual(DD.exponentBitCount, 11)
    XCTAssertEqual(DD.pi.hi, Double.pi)
  }

  /// The documented limits: the largest finite value (hi rounds to
  /// infinity beyond it), lo subnormal below 2⁻⁹⁶⁹ (the spacing stays
  /// 2⁻¹⁰⁷⁴), Double's least values.
  func testRangeLimits_AsDocumented() {
    let largest = DD.greatestFiniteMagnitude
    XCTAssertEqual(
      largest.hi + largest.lo, .greatestFiniteMagnitude,
      "largest: hi is Double's")
    XCTAssertEqual(largest.nextUp, .infinity)
    XCTAssertEqual(largest + largest.ulp, .infinity)
    XCTAssertEqual((-largest).nextDown, -.infinity)
    XCTAssertEqual(largest.ulp, DD(0x1p918))
    XCTAssertEqual(DD(0x1p1023) * 2, .infinity)
    // lo subnormal: spacing 2⁻¹⁰⁷⁴, precision lost gradually.
    let small = DD(0x1p-1000) / 3
    XCTAssert(small.lo.isSubnormal)
    XCTAssertEqual(small.ulp, .leastNonzeroMagnitude)
    XCTAssertEqual(small.nextUp - small, .leastNonzeroMagnitude)
    XCTAssertLessThanOrEqual(
      (small * 3 - DD(0x1p-1000)).magnitude, 2 * DD.leastNonzeroMagnitude)
    XCTAssertEqual(DD(0x1p-960).ulp, DD(0x1p-1065))
    XCTAssertEqual(DD.leastNonzeroMagnitude.nextDown, 0)
    XCTAssertEqual(DD.leastNormalMagnitude, DD(Double.leastNormalMagnitude))
    XCTAssertEqual(DD(0).nextUp, .leastNonzeroMagnitude)
    XCTAssertEqual((-DD.leastNonzeroMagnitude).nextUp.sign, .minus)
    XCTAssert(DD(Double.leastNonzeroMagnitude).isSubnormal)
  }

  /// Zeros keep IEEE's signs, infinities and NaNs propagate, NaN compares
  /// unequal, −0 == +0 hash alike.
  func testSpecialValues() {
    let zero = DD(0.0)
    let negativeZero = DD(-0.0)
    XCTAssertEqual((negativeZero + negativeZero).sign, .minus)
    XCTAssertEqual((negativeZero - zero).sign, .minus)
    XCTAssertEqual((zero + negativeZero).sign, .plus)
    XCTAssertEqual((DD(1) - DD(1)).sign, .plus)
    XCTAssertEqual((negativeZero * DD(5)).sign, .minus)
    XCTAssertEqual((zero / DD(-5)).sign, .minus)
    XCTAssertEqual(negativeZero.squareRoot().sign, .minus)
    XCTAssertEqual(negativeZero, zero)
    XCTAssertEqual(negativeZero.hashValue, zero.hashValue)
    XCTAssertEqual(DD(1) / zero, .infinity)
    XCTAssertEqual(DD(1) / negativeZero, -.infinity)
    XCTAssert((zero / zero).isNaN)
    XCTAssert((DD.infinity - .infinity).isNaN)
    XCTAssert((DD.infinity * zero).isNaN)
    XCTAssertEqual(DD.infinity + 1, .infinity)
    XCTAssertEqual(DD(3) / .infinity, 0)
    XCTAssert(DD(-1).squareRoot().isNaN)
    XCTAssertEqual(DD.infinity.squareRoot(), .infinity)
    XCTAssert((DD.nan + 1).isNaN)
    XCTAssertNotEqual(DD.nan, .nan)
    XCTAssertFalse(DD.nan < 1 || DD.nan > 1)
    XCTAssert(DD.signalingNaN.isSignalingNaN)
    XCTAssertEqual(DD.infinity.exponentBitPattern, 2047)
    XCTAssertEqual(DD.infinity.significandBitPattern, 0)
    XCTAssert(
      DD(sign: .plus, exponentBitPattern: 2047, significandBitPattern: 1)
        .isNaN)
    XCTAssertEqual(DD.nan.significandWidth, -1)
    XCTAssertEqual(zero.significandWidth, -1)
    XCTAssertEqual(DD(-1).magnitude, 1)
  }

  /// Rounding to integers by every rule, where lo decides (the tail below
  /// hi's half-integer) and where hi is an integer and lo is not.
  func testRounded_EveryRule() {
    let justAbove = DD(2.5, 0x1p-60)
    let justBelow = DD(2.5, -0x1p-60)
    XCTAssertEqual(justAbove.rounded(.toNearestOrEven), 3)
    XCTAssertEqual(justBelow.rounded(.toNearestOrEven), 2)
    XCTAssertEqual(DD(2.5).rounded(.toNearestOrEven), 2)
    XCTAssertEqual(DD(3.5).rounded(.toNearestOrEven), 4)
    XCTAssertEqual(DD(-2.5).rounded(.toNearestOrAwayFromZero), -3)
    XCTAssertEqual(DD(-2.5, 0x1p-60).rounded(.toNearestOrAwayFromZero), -2)
    let big = DD(0x1p60, 0.5)
    XCTAssertEqual(big.rounded(.toNearestOrEven), DD(0x1p60))
    XCTAssertEqual(big.rounded(.toNearestOrAwayFromZero), DD(0x1p60, 1))
    XCTAssertEqual(big.rounded(.up), DD(0x1p60, 1))
    XCTAssertEqual(big.rounded(.down), DD(0x1p60))
    XCTAssertEqual((-big).rounded(.towardZero), -DD(0x1p60))
    XCTAssertEqual((-big).rounded(.awayFromZero), -DD(0x1p60, 1))
    XCTAssertEqual(DD(0x1p60, -0.25).rounded(.down), DD(0x1p60, -1))
    XCTAssertEqual(DD(-0.3).rounded(.towardZero).sign, .minus)
    XCTAssertEqual(DD(0x1p80, 3).rounded(.down), DD(0x1p80, 3))
    // Remainders, exact.
    XCTAssertEqual(DD(11).remainder(dividingBy: 2), -1)
    XCTAssertEqual(DD(-7.5).remainder(dividingBy: 2), 0.5)
    // 2¹⁰⁰ ≡ 1 (mod 3).
    XCTAssertEqual(DD(0x1p100, 1).truncatingRemainder(dividingBy: 3), 2)
    XCTAssertEqual(DD(-0x1p100, -1).truncatingRemainder(dividingBy: 3), -2)
  }
}
