import XCTest

@testable import Geometry
@testable import ExactArithmetic
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
}
