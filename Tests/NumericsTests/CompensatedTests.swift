import XCTest

@testable import Geometry
@testable import Numerics
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

  /// A planet of radius 1e8 seen from 1 above its surface: c = (1e8 + 1)² −
  /// 1e16 = 2e8 + 1, exact in Double, where plain evaluation gives 2e8 (or
  /// worse); rounded once for Float output.
  func testCameraRelativeSphere_PlanetFromDouble() {
    let centre = Vector3<Double>(0, -1e8, 0)
    let eye = Vector3<Double>(0, 1, 0)
    let double = CameraRelative.sphere(
      center: centre, radius: 1e8, eye: eye, as: Double.self)
    XCTAssertEqual(double.c, 2e8 + 1)
    XCTAssertEqual(double.offset, Vector3(0, -1e8 - 1, 0))
    let plain = (centre - eye).lengthSquared - 1e8 * 1e8
    XCTAssertNotEqual(plain, 2e8 + 1, "plain evaluation was expected to fail")

    let float = CameraRelative.sphere(
      center: centre, radius: 1e8, eye: eye, as: Float.self)
    XCTAssertEqual(float.c, Float(2e8 + 1), "2e8 + 1 rounded once")
    XCTAssertEqual(float.offset, Vector3<Float>(0, Float(-1e8 - 1), 0))

    // Beyond Double's reach: (1e17 + 1)² − 1e34 = 2e17 + 1 needs 58 bits,
    // so it is exact only as Float80 and rounded once as Double.
    let far = Vector3<Double>(0, -1e17, 0)
    let wide = CameraRelative.sphere(
      center: far, radius: 1e17, eye: eye, as: ReferenceScalar.self)
    XCTAssertEqual(wide.c, 200_000_000_000_000_001)
    let narrow = CameraRelative.sphere(
      center: far, radius: 1e17, eye: eye, as: Double.self)
    XCTAssertEqual(narrow.c, Double(200_000_000_000_000_001 as ReferenceScalar))
  }

  /// Narrowing to a smaller type is documented as one rounding (the
  /// offset "rounded to nearest", c "rounded once to S"), but a Double
  /// pair (sum, error) is narrowed to Float as S(sum) + S(error), or as
  /// S(Sum2 in Double): two roundings. When the Double sum lies exactly
  /// halfway between two Floats and only the error term breaks the tie,
  /// the tie goes to even instead: 1 + 2^−24 + 2^−60 must round up to
  /// 1 + 2^−23, and comes out as 1. (At most one Float ulp, in ties only.)
  func testCameraRelative_NarrowingRoundsOnce() {
    let relative = CameraRelative.sphere(
      center: Vector3<Double>(1 + 0x1p-24, 0, 0), radius: 0.5,
      eye: Vector3(-0x1p-60, 0, 0), as: Float.self)
    XCTAssertEqual(relative.offset.x, 1 + 0x1p-23, "offset, rounded once")
    var terms: [Double] = [1 + 0x1p-24, 0x1p-60]
    let c: Float = terms.withUnsafeMutableBufferPointer {
      CameraRelative.roundedSum($0)
    }
    XCTAssertEqual(c, 1 + 0x1p-23, "Sum2, rounded once")
  }

  /// The same from Float inputs: radius 1e6, c = 2e6 + 1 < 2^24 is exact in
  /// Float, where plain Float evaluation loses every digit (ulp of 1e12 is
  /// 65536).
  func testCameraRelativeSphere_PlanetFromFloat() {
    let centre = Vector3<Float>(0, -1e6, 0)
    let eye = Vector3<Float>(0, 1, 0)
    let relative = CameraRelative.sphere(
      center: centre, radius: 1e6, eye: eye, as: Float.self)
    XCTAssertEqual(relative.c, 2_000_001)
    XCTAssertEqual(relative.offset, Vector3(0, -1_000_001, 0))
    let plain = (centre - eye).lengthSquared - Float(1e6) * Float(1e6)
    XCTAssertGreaterThan(
      (Double(plain) - 2_000_001).magnitude, 1e4,
      "plain evaluation was expected to fail")
  }

  /// Random integer scenes, exact in Int128: c within one rounding of
  /// |centre − eye|² − r², however close the eye is to the surface.
  @available(macOS 15.0, *)
  func checkCameraRelativeRandom<T: RayScalar>(_: T.Type, base: UInt64) {
    // Coordinates below 2^(p/2 + 4) make squares of up to p + 8 bits:
    // inexact in T, exact in Int128 and in ReferenceScalar.
    let limit = Int64(1) << (T.significandBitCount / 2 + 4)
    forEachSeed(5000, base: base) { generator, seed in
      func point() -> (Int64, Int64, Int64) {
        (
          .random(in: -limit...limit, using: &generator),
          .random(in: -limit...limit, using: &generator),
          .random(in: -limit...limit, using: &generator)
        )
      }
      let (centre, eye) = (point(), point())
      let p = (
        Int128(centre.0 - eye.0), Int128(centre.1 - eye.1),
        Int128(centre.2 - eye.2)
      )
      let squared = p.0 * p.0 + p.1 * p.1 + p.2 * p.2
      // A radius whose square is close to |p|²: the eye within a few units
      // of the surface, on either side.
      let radius = max(
        1,
        Int64(Double(squared).squareRoot().rounded())
          + Int64.random(in: -3...3, using: &generator))
      let exact = squared - Int128(radius) * Int128(radius)
      let relative = CameraRelative.sphere(
        center: Vector3<T>(T(centre.0), T(centre.1), T(centre.2)),
        radius: T(radius),
        eye: Vector3<T>(T(eye.0), T(eye.1), T(eye.2)), as: T.self)
      XCTAssertEqual(
        relative.offset, Vector3(T(p.0), T(p.1), T(p.2)),
        "seed \(seed): exact in T")
      // Rounded once, to nearest: at most u = ε/2 relatively, 0.5 ulps.
      assertRelativeError(
        relative.c, ReferenceScalar(exact), ulps: 0.5,
        "seed \(seed): rounded once")
    }
  }

  func testCameraRelativeSphere_Random_Float() throws {
    guard #available(macOS 15.0, *) else { throw XCTSkip(Self.int128) }
    checkCameraRelativeRandom(Float.self, base: 0xCA3E_1001)
  }
  func testCameraRelativeSphere_Random_Double() throws {
    guard #available(macOS 15.0, *) else { throw XCTSkip(Self.int128) }
    checkCameraRelativeRandom(Double.self, base: 0xCA3E_1002)
  }

  /// k = offset − n·eye without cancellation: an eye 1 above the plane
  /// y = 1e8 seen from 1e8 + 1 gives k = −1 exactly.
  func testCameraRelativePlane() {
    let k: Double = CameraRelative.plane(
      normal: Vector3<Double>(0, 1, 0), offset: 1e8,
      eye: Vector3(5, 1e8 + 1, -7))
    XCTAssertEqual(k, -1)
    // n = (0.6, 0.8, 0) rounded to Double and an eye of 2-bit integers
    // times 2^23: the products (≤ 55 bits), their sum and its difference
    // with the offset are all exact in ReferenceScalar, and n·eye cancels
    // against the offset down to the products' rounding errors, which the
    // compensated sum keeps.
    let n = Vector3<Double>(0.6, 0.8, 0)
    let eye = Vector3<Double>(3 * 0x1p23, 4 * 0x1p23, 0)
    let offset = 5 * 0x1p23 + 0.25
    let exact = ReferenceScalar(offset) - n.reference.dot(eye.reference)
    let got: Double = CameraRelative.plane(normal: n, offset: offset, eye: eye)
    assertRelativeError(got, exact, ulps: 0.5, "rounded once")
    let plain = offset - n.dot(eye)
    XCTAssertGreaterThan(
      relativeErrorInUlps(plain, exact), 1e3,
      "plain evaluation was expected to fail")
  }
}
