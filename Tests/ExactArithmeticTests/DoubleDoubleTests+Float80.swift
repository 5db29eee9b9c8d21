import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

extension DoubleDoubleTests {
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
}
