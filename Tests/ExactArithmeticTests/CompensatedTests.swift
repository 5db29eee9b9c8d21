import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

final class CompensatedTests: XCTestCase {
  /// The exact integer checks use Int128, which macOS has from 15 on.
  static let int128 = "Int128 needs macOS 15; Linux always has it"

  // MARK: - Error-free transformations

  /// s + e == a + b exactly and s = fl(a + b), for Floats whose sum is
  /// exact in Double: magnitudes within 2^27 of each other fit 24 + 27 + 1
  /// bits, under Double's 53.
  func testTwoSum_ExactInFloat() {
    forEachSeed(20_000, base: 0x7150_0001) { generator, seed in
      let a = generator.sign(Float.self) * generator.logUniform(1e-4, 1e4)
      let b = generator.sign(Float.self) * generator.logUniform(1e-4, 1e4)
      let (sum, error) = Compensated.twoSum(a, b)
      XCTAssertEqual(sum, a + b, "seed \(seed)")
      XCTAssertEqual(
        Double(sum) + Double(error), Double(a) + Double(b),
        "seed \(seed): \(a) + \(b)")
      XCTAssertLessThanOrEqual(error.magnitude, sum.ulp / 2, "seed \(seed)")
    }
  }

  /// p + e == a·b exactly and p = fl(a·b): the product of two Floats has at
  /// most 48 bits, exact in Double, and so is p + e.
  func testTwoProduct_ExactInFloat() {
    forEachSeed(20_000, base: 0x7150_0002) { generator, seed in
      let a = generator.sign(Float.self) * generator.logUniform(1e-15, 1e15)
      let b = generator.sign(Float.self) * generator.logUniform(1e-15, 1e15)
      let (product, error) = Compensated.twoProduct(a, b)
      XCTAssertEqual(product, a * b, "seed \(seed)")
      XCTAssertEqual(
        Double(product) + Double(error), Double(a) * Double(b),
        "seed \(seed): \(a)·\(b)")
    }
  }

  /// The same in Double, checked in integers: for integer-valued Doubles
  /// below 2^53, a + b and a·b (< 2^106) are exact in Int128, and so are
  /// the integer-valued s, p and e.
  /// Dekker's product of Veltkamp's halves gives the fused multiply-add's
  /// exact error, bit for bit, over the components of unit vectors and
  /// well beyond (magnitudes 2^-200 to 2^200, random signs and bits).
  func testSplitProduct_SameAsFusedMultiplyAdd() {
    forEachSeed(50_000, base: 0x7150_0009) { generator, seed in
      func value() -> Double {
        let significand = Double.random(in: 1..<2, using: &generator)
        let exponent = Int.random(in: -200...200, using: &generator)
        let sign: FloatingPointSign =
          Bool.random(using: &generator)
          ? .minus : .plus
        return Double(sign: sign, exponent: exponent, significand: significand)
      }
      let (a, b) = (value(), value())
      let split = Compensated.splitProduct(a, b)
      let fused = Compensated.twoProduct(a, b)
      XCTAssertEqual(split.product, fused.product, "seed \(seed): \(a)·\(b)")
      XCTAssertEqual(split.error, fused.error, "seed \(seed): \(a)·\(b)")
    }
  }

  func testTwoSumAndTwoProduct_ExactInDouble() throws {
    guard #available(macOS 15.0, *) else { throw XCTSkip(Self.int128) }
    forEachSeed(20_000, base: 0x7150_0003) { generator, seed in
      func integer() -> Int64 {
        let bits = Int.random(in: 0...53, using: &generator)
        return Int64.random(in: -(1 << bits)...(1 << bits), using: &generator)
      }
      let (integerA, integerB) = (integer(), integer())
      let (a, b) = (Double(integerA), Double(integerB))
      let (sum, sumError) = Compensated.twoSum(a, b)
      XCTAssertEqual(sum, a + b, "seed \(seed)")
      XCTAssertEqual(
        Int128(exactly: sum).flatMap { s in
          Int128(exactly: sumError).map { s + $0 }
        },
        Int128(integerA) + Int128(integerB), "seed \(seed): twoSum(\(a), \(b))")
      let (product, productError) = Compensated.twoProduct(a, b)
      XCTAssertEqual(product, a * b, "seed \(seed)")
      XCTAssertEqual(
        Int128(exactly: product).flatMap { p in
          Int128(exactly: productError).map { p + $0 }
        },
        Int128(integerA) * Int128(integerB),
        "seed \(seed): twoProduct(\(a), \(b))")
    }
  }

  // MARK: - Dot2 and Sum2

  /// An ill-conditioned dot product of integer-valued vectors, computed
  /// exactly in Int128: the third pair is chosen to cancel the first two,
  /// so the condition number Σ|aᵢbᵢ| / |a·b| reaches far beyond 1/ε.
  /// Ogita, Rump and Oishi's bound for Dot2 is
  /// |res − a·b| ≤ u·|a·b| + γ₃²·Σ|aᵢbᵢ|, with u = ε/2 and γ₃ = 3u/(1 − 3u).
  @available(macOS 15.0, *)
  func checkDot<T: RayScalar>(_: T.Type, base: UInt64) {
    let limit = Int64(1) << (T.significandBitCount + 1)
    let u = ReferenceScalar(T.ulpOfOne) / 2
    let gamma3 = 3 * u / (1 - 3 * u)
    var largestCondition: ReferenceScalar = 0
    var plainWorst: ReferenceScalar = 0
    forEachSeed(5000, base: base) { generator, seed in
      func integer() -> T {
        T(Int64.random(in: (1 - limit)...(limit - 1), using: &generator))
      }
      let a = Vector3<T>(integer(), integer(), integer())
      var b = Vector3<T>(integer(), integer(), 0)
      guard a.z != 0 else { return }
      // b.z ≈ −(a.x b.x + a.y b.y)/a.z, an integer; skip the cases where it
      // would leave the integers of T.
      let third =
        -(ReferenceScalar(a.x) * ReferenceScalar(b.x)
        + ReferenceScalar(a.y) * ReferenceScalar(b.y)) / ReferenceScalar(a.z)
      guard third.magnitude < ReferenceScalar(limit) else { return }
      b.z = T(third.rounded())
      let products = (0..<3).map { Int128(a[$0]) * Int128(b[$0]) }
      let exact = products.reduce(0, +)
      guard exact != 0 else { return }
      let magnitudes = ReferenceScalar(products.map(\.magnitude).reduce(0, +))
      let got = Compensated.dot(a, b)
      guard let integerGot = Int128(exactly: got) else {
        XCTFail("seed \(seed): \(got) is not an integer")
        return
      }
      let error = ReferenceScalar((integerGot - exact).magnitude)
      let bound =
        u * ReferenceScalar(exact.magnitude) + gamma3 * gamma3 * magnitudes
      XCTAssertLessThanOrEqual(
        error, bound, "seed \(seed): \(a)·\(b) = \(exact), got \(got)")
      largestCondition = max(
        largestCondition, magnitudes / ReferenceScalar(exact.magnitude))
      if let plain = Int128(exactly: a.dot(b)) {
        plainWorst = max(
          plainWorst,
          ReferenceScalar((plain - exact).magnitude)
            / ReferenceScalar(exact.magnitude))
      }
    }
    print(
      "\(T.self) Dot2: largest condition \(largestCondition), plain worst "
        + "\(plainWorst)"
    )
    // The test is only worth something if it reaches the ill-conditioned
    // cases where plain evaluation has no correct digit left.
    XCTAssertGreaterThan(largestCondition, 1 / ReferenceScalar(T.ulpOfOne))
    XCTAssertGreaterThan(
      plainWorst, 1, "plain a·b was expected to lose every digit")
  }

  func testDot_IllConditioned_Float() throws {
    guard #available(macOS 15.0, *) else { throw XCTSkip(Self.int128) }
    checkDot(Float.self, base: 0xD072_0001)
  }
  func testDot_IllConditioned_Double() throws {
    guard #available(macOS 15.0, *) else { throw XCTSkip(Self.int128) }
    checkDot(Double.self, base: 0xD072_0002)
  }

  /// Float inputs against the reference (Float80 on x86), as in a renderer's
  /// Float path: products
  /// of Floats are exact in Float80 and their sum is off by at most 2^−64
  /// of the largest partial sum, far below a Float ulp of the result for
  /// these condition numbers (≤ 1e9). Within the Dot2 bound.
  func testDot_FloatAgainstReference() {
    let u = ReferenceScalar(Float.ulpOfOne) / 2
    let gamma3 = 3 * u / (1 - 3 * u)
    forEachSeed(5000, base: 0xD072_0003) { generator, seed in
      let a = generator.unitVector(Float.self) * generator.logUniform(1e-3, 1e3)
      let tangent = a.cross(generator.unitVector(Float.self))
      // b nearly perpendicular to a, by a log-uniform slope.
      let b = tangent + a * generator.logUniform(1e-9, 1)
      let want = a.reference.dot(b.reference)
      let terms = a.reference * b.reference
      let magnitudes = terms.x.magnitude + terms.y.magnitude + terms.z.magnitude
      let got = Compensated.dot(a, b)
      let bound =
        u * want.magnitude + gamma3 * gamma3 * magnitudes
        + 0x1p-63 * magnitudes  // the reference's own rounding
      XCTAssertLessThanOrEqual(
        (ReferenceScalar(got) - want).magnitude, bound, "seed \(seed)")
    }
  }

  /// Sum2 recovers what plain summation loses entirely.
  func testSum_Cancellation() {
    XCTAssertEqual(Compensated.sum([1e16, 1, -1e16] as [Double]), 1)
    XCTAssertEqual(Compensated.sum([1, 1e100, 1, -1e100] as [Double]), 2)
    XCTAssertEqual(Compensated.sum([1e8, 1, -1e8] as [Float]), 1)
    XCTAssertEqual(Compensated.sum([] as [Double]), 0)
    XCTAssertEqual(Compensated.sum([0.5] as [Double]), 0.5)
  }

  // MARK: - Camera-relative constants
}
