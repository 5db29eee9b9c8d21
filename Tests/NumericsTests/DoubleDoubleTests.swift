import XCTest

@testable import Geometry
@testable import Numerics
import TestSupport

/// DoubleDouble against exact arithmetic and against Float80.
///
/// Errors are measured exactly where they matter: x + y − z, x·y − z,
/// x − z·y and x − z² are formed as Shewchuk expansions (sums of
/// non-overlapping Doubles built from error-free transformations), so the
/// error of z is known to Double's precision, far below the 2⁻¹⁰⁶ being
/// tested. Bounds are in units of u² = 2⁻¹⁰⁶ (u = 2⁻⁵³), relative to the
/// exact result, and are the documented ones (see `DoubleDouble`). Inputs
/// are random with log-uniform magnitudes over ranges where no product's
/// error term underflows, seeded per iteration; a failure prints its seed.
final class DoubleDoubleTests: XCTestCase {
  typealias DD = DoubleDouble
  static let uSquared = 0x1p-106

  // MARK: - Helpers

  /// The exact sum of `terms` as an expansion, smallest component first
  /// (Shewchuk's Grow-Expansion; exact barring overflow and underflow).
  func expansion(_ terms: [Double]) -> [Double] {
    var components: [Double] = []
    for term in terms {
      var carry = term
      var next: [Double] = []
      for component in components {
        let (sum, error) = Compensated.twoSum(carry, component)
        if error != 0 { next.append(error) }
        carry = sum
      }
      if carry != 0 { next.append(carry) }
      components = next
    }
    return components
  }

  /// The expansion's value to Double's precision.
  func value(_ components: [Double]) -> Double {
    components.reduce(0, +)
  }

  /// The four exact products making up a·b.
  func productTerms(_ a: DD, _ b: DD) -> [Double] {
    var terms: [Double] = []
    for (x, y) in [(a.hi, b.hi), (a.hi, b.lo), (a.lo, b.hi), (a.lo, b.lo)] {
      let (p, e) = Compensated.twoProduct(x, y)
      terms += [p, e]
    }
    return terms
  }

  /// A random double-double with all 106 bits in use: a log-uniform leading
  /// part with a random sign and a uniformly random tail.
  func random(
    _ generator: inout SplitMix64, _ low: Double, _ high: Double
  ) -> DD {
    let hi = generator.sign(Double.self) * generator.logUniform(low, high)
    let tail = hi * 0x1p-53 * Double.random(in: -1...1, using: &generator)
    return DD(hi, tail)
  }

  /// Whether `x` is in the normalised 106-bit form the type promises.
  func assertCanonical(
    _ x: DD, _ context: @autoclosure () -> String,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    guard x.isFinite, x != 0 else { return }
    XCTAssertEqual(x.hi + x.lo, x.hi, context(), file: file, line: line)
    let quantum = Swift.max(x.exponent - 105, -1074)
    let scaled = x.lo / Double(sign: .plus, exponent: quantum, significand: 1)
    XCTAssertEqual(
      scaled, scaled.rounded(), "\(context()): lo off the 106-bit grid",
      file: file, line: line)
  }

  // MARK: - Error-free transformations

  #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
    /// s + e == a + b exactly and s = fl(a + b) for Doubles: checked in
    /// Float80, which holds the sum exactly when the exponents are within
    /// 10 of each other (53 + 10 + 1 ≤ 64 bits).
    func testTwoSum_ExactForDoubles() {
      forEachSeed(20_000, base: 0xDD00_0001) { generator, seed in
        let a = generator.sign(Double.self) * generator.logUniform(1.0, 2.0)
        let b =
          generator.sign(Double.self)
          * generator.logUniform(0x1p-9, 0x1p9)
        let (sum, error) = Compensated.twoSum(a, b)
        XCTAssertEqual(sum, a + b, "seed \(seed)")
        XCTAssertEqual(
          Float80(sum) + Float80(error), Float80(a) + Float80(b),
          "seed \(seed): \(a) + \(b)")
      }
    }

    /// p + e == a·b exactly for Doubles with 32-bit significands, whose
    /// product (64 bits) Float80 holds exactly.
    func testTwoProduct_ExactForDoubles() {
      forEachSeed(20_000, base: 0xDD00_0002) { generator, seed in
        let scaleA = Double(
          sign: .plus,
          exponent: Int.random(
            in: -250...250, using: &generator), significand: 1)
        let scaleB = Double(
          sign: .plus,
          exponent: Int.random(
            in: -250...250, using: &generator), significand: 1)
        let a =
          Double(UInt32.random(in: 1...UInt32.max, using: &generator))
          * scaleA
        let b =
          -Double(UInt32.random(in: 1...UInt32.max, using: &generator))
          * scaleB
        let (product, error) = Compensated.twoProduct(a, b)
        XCTAssertEqual(product, a * b, "seed \(seed)")
        XCTAssertEqual(
          Float80(product) + Float80(error), Float80(a) * Float80(b),
          "seed \(seed): \(a)·\(b)")
      }
    }
  #endif

  // MARK: - Arithmetic against exact results

  /// x + y: ≤ 3u²/(1 − 4u) for the algorithm plus u² for rounding to the
  /// 106-bit format, so ≤ 4u²·(1 + 2⁻⁴⁸). A quarter of the pairs nearly
  /// cancel (y = −x·(1 + δ), |δ| ≤ 2⁻²⁰).
  func testAddition_ErrorBoundExact() {
    var worst = 0.0
    forEachSeed(20_000, base: 0xDD00_0010) { generator, seed in
      let x = random(&generator, 0x1p-400, 0x1p400)
      var y = random(&generator, 0x1p-400, 0x1p400)
      if generator.next() % 4 == 0 {
        let delta = random(&generator, 0x1p-80, 0x1p-20)
        y = -x * (1 + delta)
      }
      let z = x + y
      assertCanonical(z, "seed \(seed)")
      let exact = expansion([x.hi, x.lo, y.hi, y.lo])
      let error = expansion([z.hi, z.lo, -x.hi, -x.lo, -y.hi, -y.lo])
      if exact.isEmpty {
        XCTAssertEqual(z, 0, "seed \(seed)")
        return
      }
      let units =
        value(error).magnitude / value(exact).magnitude
        / Self.uSquared
      worst = Swift.max(worst, units)
      XCTAssertLessThanOrEqual(
        units, 4 * (1 + 0x1p-48), "seed \(seed): \(x) + \(y) = \(z)")
    }
    print("DoubleDouble +: worst \(worst) u²")
  }

  /// x·y: ≤ 4u² (Algorithm 12 with FMA) plus u² for the rounding: ≤ 5u².
  func testMultiplication_ErrorBoundExact() {
    var worst = 0.0
    forEachSeed(20_000, base: 0xDD00_0011) { generator, seed in
      let x = random(&generator, 0x1p-200, 0x1p200)
      let y = random(&generator, 0x1p-200, 0x1p200)
      let z = x * y
      assertCanonical(z, "seed \(seed)")
      let exact = productTerms(x, y)
      let error = expansion([z.hi, z.lo] + exact.map { -$0 })
      let units =
        value(error).magnitude / value(expansion(exact)).magnitude
        / Self.uSquared
      worst = Swift.max(worst, units)
      XCTAssertLessThanOrEqual(units, 5, "seed \(seed): \(x)·\(y) = \(z)")
    }
    print("DoubleDouble ×: worst \(worst) u²")
  }

  /// x/y: the residual x − z·y is exact as an expansion and
  /// |z − x/y|/|x/y| = |x − z·y|/|x|. Bound 2u²·(1 + 2⁻⁴⁰): one rounding
  /// of the tail and one to 106 bits, the Newton steps' truncation O(u³).
  func testDivision_ErrorBoundExact() {
    var worst = 0.0
    forEachSeed(20_000, base: 0xDD00_0012) { generator, seed in
      let x = random(&generator, 0x1p-200, 0x1p200)
      let y = random(&generator, 0x1p-200, 0x1p200)
      let z = x / y
      assertCanonical(z, "seed \(seed)")
      let residual = expansion([x.hi, x.lo] + productTerms(z, y).map { -$0 })
      let units = value(residual).magnitude / x.hi.magnitude / Self.uSquared
      worst = Swift.max(worst, units)
      XCTAssertLessThanOrEqual(
        units, 2 * (1 + 0x1p-40), "seed \(seed): \(x)/\(y) = \(z)")
    }
    print("DoubleDouble ÷: worst \(worst) u²")
  }

  /// √x: the residual x − z² is exact as an expansion and, with z ≈ √x,
  /// |z − √x|/√x = |x − z²|/(z + √x)/√x ≈ |x − z²|/(2x). Bound as for ÷.
  func testSquareRoot_ErrorBoundExact() {
    var worst = 0.0
    forEachSeed(20_000, base: 0xDD00_0013) { generator, seed in
      let x = random(&generator, 0x1p-400, 0x1p400).magnitude
      let z = x.squareRoot()
      assertCanonical(z, "seed \(seed)")
      let residual = expansion([x.hi, x.lo] + productTerms(z, z).map { -$0 })
      let units =
        value(residual).magnitude / (2 * x.hi) / Self.uSquared
      worst = Swift.max(worst, units)
      XCTAssertLessThanOrEqual(
        units, 2 * (1 + 0x1p-40), "seed \(seed): √\(x) = \(z)")
    }
    print("DoubleDouble √: worst \(worst) u²")
  }

  /// Integers: products of two below 2⁵³ fit 106 bits and come out exact
  /// (checked against UInt64's full-width product, through the generic
  /// conversion to DoubleDoubleSignificand), and so do the quotient back
  /// and the square root of a square.
  func testIntegers_ExactProductsQuotientsAndRoots() {
    forEachSeed(5_000, base: 0xDD00_0014) { generator, seed in
      let a = UInt64.random(in: 1..<(1 << 53), using: &generator)
      let b = UInt64.random(in: 1..<(1 << 53), using: &generator)
      let product = DD(Double(a)) * DD(Double(b))
      let full = a.multipliedFullWidth(by: b)
      XCTAssertEqual(
        DoubleDoubleSignificand(exactly: product),
        DoubleDoubleSignificand(high: full.high, low: full.low),
        "seed \(seed): \(a)·\(b)")
      XCTAssertEqual(
        DD(DoubleDoubleSignificand(high: full.high, low: full.low)), product,
        "seed \(seed)")
      XCTAssertEqual(product / DD(Double(b)), DD(Double(a)), "seed \(seed)")
      XCTAssertEqual(
        (DD(Double(a)) * DD(Double(a))).squareRoot(), DD(Double(a)),
        "seed \(seed)")
      XCTAssertEqual(UInt64(exactly: DD(a) * DD(1)), a, "seed \(seed)")
    }
    // 3⁴⁰ < 2⁶⁴ by repeated squaring, exact.
    XCTAssertEqual(UInt64(exactly: DD.pow(3, 40)), 12_157_665_459_056_928_801)
    // Rounding of wide integers: 2¹⁰⁶ + 1 is a tie, to even.
    let wide = DoubleDoubleSignificand(high: 1 << 42, low: 1)
    XCTAssertEqual(DD(wide), DD(0x1p106))
    XCTAssertNil(DD(exactly: wide))
    XCTAssertEqual(DD(wide + 2), DD(0x1p106, 4))
  }

  // MARK: - Against Float80

  #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
    /// +, −, ×, ÷, √ of Float80 values (exact in DoubleDouble) against
    /// Float80's correctly rounded results: they differ by Float80's
    /// rounding, ≤ 2⁻⁶⁴ relative, plus DoubleDouble's ≤ 5u².
    func testArithmetic_AgainstFloat80() {
      let bound = 0x1p-64 + 5 * Self.uSquared
      func check(
        _ got: DD, _ want: Float80, _ what: String, _ seed: UInt64
      ) {
        guard want != 0 else { return XCTAssertEqual(got, 0, what) }
        let difference = (got - DD(want)).magnitude / DD(want).magnitude
        XCTAssertLessThanOrEqual(
          Double(difference), bound, "seed \(seed): \(what)")
      }
      forEachSeed(10_000, base: 0xDD00_0020) { generator, seed in
        let a =
          Float80(generator.sign(Double.self))
          * Float80(generator.logUniform(0x1p-300, 0x1p300))
          * (1 + Float80(UInt64.random(in: 0...UInt64.max, using: &generator))
            * 0x1p-66)
        let b =
          Float80(generator.sign(Double.self))
          * Float80(generator.logUniform(0x1p-300, 0x1p300))
          * (1 + Float80(UInt64.random(in: 0...UInt64.max, using: &generator))
            * 0x1p-66)
        let (x, y) = (DD(a), DD(b))
        XCTAssertEqual(Float80(x), a, "seed \(seed): exact conversion")
        check(x + y, a + b, "\(a) + \(b)", seed)
        check(x - y, a - b, "\(a) − \(b)", seed)
        check(x * y, a * b, "\(a)·\(b)", seed)
        check(x / y, a / b, "\(a)/\(b)", seed)
        check(x.magnitude.squareRoot(), a.magnitude.squareRoot(), "√", seed)
      }
    }

    /// Conversions to Float80 and Double by the standard library's generic
    /// path, which reads the model's fields (exponent, significand bit
    /// pattern, significandWidth), against single roundings of hi + lo.
    func testConversions_CorrectlyRounded() {
      forEachSeed(10_000, base: 0xDD00_0021) { generator, seed in
        let x = random(&generator, 0x1p-1000, 0x1p1000)
        XCTAssertEqual(Double(x), x.hi, "seed \(seed)")
        XCTAssertEqual(
          Float80(x), Float80(x.hi) + Float80(x.lo), "seed \(seed): \(x)")
      }
      // Just above a Float midpoint: Float(hi) alone would round to even.
      let x = DD(1 + 0x1p-24, 0x1p-80)
      XCTAssertEqual(Float(x), 1 + 0x1p-23)
      XCTAssertEqual(Float(x.hi), 1)
    }

    /// sin and cos against Float80's (each within about an ulp of
    /// Float80, 2⁻⁶³): within 2⁻⁶² of the larger of the value and 2⁻⁶⁴
    /// (near zeros the reduction's absolute error counts) over |x| < 10⁴;
    /// and, to double-double precision, sin² + cos² = 1 within 16u² and
    /// sin(π/6) = ½ within 8u² (π is rounded to 106 bits).
    func testSineAndCosine_AgainstFloat80() {
      forEachSeed(2_000, base: 0xDD00_0022) { generator, seed in
        let a =
          generator.sign(Double.self)
          * generator.logUniform(1e-3, 1e4)
        // A Float80 argument (exact in DoubleDouble), so that both
        // evaluate at the same point.
        let f =
          Float80(a)
          * (1 + Float80(UInt64.random(in: 0...UInt64.max, using: &generator))
            * 0x1p-66)
        let x = DD(f)
        for (got, want, name) in [
          (DD.sin(x), sinl(f), "sin"), (DD.cos(x), cosl(f), "cos"),
        ] {
          let scale = Swift.max(want.magnitude, 0x1p-64)
          let difference = (got - DD(want)).magnitude / DD(scale)
          XCTAssertLessThanOrEqual(
            Double(difference), 0x1p-62, "seed \(seed): \(name) \(x)")
        }
        let one = DD.sin(x) * DD.sin(x) + DD.cos(x) * DD.cos(x)
        XCTAssertLessThanOrEqual(
          Double((one - 1).magnitude), 16 * Self.uSquared, "seed \(seed)")
      }
      XCTAssertLessThanOrEqual(
        Double((DD.sin(DD.pi / 6) - 0.5).magnitude), 8 * Self.uSquared)
      XCTAssertLessThanOrEqual(
        Double((DD.tan(DD.pi / 4) - 1).magnitude), 16 * Self.uSquared)
    }

    /// The through-Double functions are Double-accurate, as documented.
    func testDoubleAccurateFunctions_AgainstFloat80() {
      let x = DD(0.625)
      let cases: [(DD, Float80)] = [
        (DD.pow(x, DD(1.5)), powl(0.625, 1.5)),
        (DD.sin(DD(0x1p31)), sinl(0x1p31)),
      ]
      for (got, want) in cases {
        XCTAssertEqual(
          Double(Float80(got)), Double(want), accuracy: 2 * Double(want).ulp)
      }
    }
  #endif

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
