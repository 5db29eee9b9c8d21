import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `specularPower` (the fast engine's highlight^shininess) against xⁿ in
/// double-double (relative error near 2n·2⁻¹⁰⁴, far below the bound
/// tested), and against the C library's `pow` wherever it hands over.
final class SpecularPowerTests: XCTestCase {
  /// The highlights a unit normal and direction give, (0, 1 + 4ε], and the
  /// whole shininesses 2…1024, each end and a spread between.
  func cases(seed: UInt64) -> [(x: Double, n: Int)] {
    var generator = SplitMix64(seed: seed)
    let exponents = [
      2, 3, 4, 5, 7, 8, 10, 12, 20, 40, 50, 99, 100, 128, 255,
      511, 512, 513, 1000, 1023, 1024,
    ]
    var cases: [(x: Double, n: Int)] = []
    for n in exponents {
      for _ in 0..<400 {
        // Uniform in (0, 1], and near 1, where highlights gather.
        let uniform = Double(generator.next() >> 11 + 1) * 0x1p-53
        let near = 1 - Double(generator.next() % 4096) * 0x1p-40
        cases += [(uniform, n), (near, n)]
      }
      cases += [(1, n), (1 + 4 * .ulpOfOne, n), (0.5, n), (0x1p-30, n)]
    }
    return cases
  }

  /// Double: within (1 + 2⁻⁵³)²ⁿ − 1 of xⁿ relative, where xⁿ is normal.
  func testDouble_WithinTheStatedBound() {
    for (x, n) in cases(seed: 3) {
      let exact = DoubleDouble.pow(DoubleDouble(x), n)
      guard exact.hi >= Double.leastNormalMagnitude else { continue }
      let computed = specularPower(x, Double(n))
      let error =
        ((DoubleDouble(computed) - exact) / exact).hi.magnitude
      // (1 + 2⁻⁵³)²ⁿ − 1 exceeds 2n·2⁻⁵³ by less than 2⁻⁴⁰ of itself for
      // n ≤ 1024; the reference's own error is near 2n·2⁻¹⁰⁴.
      let bound = 2 * Double(n) * 0x1p-53 * (1 + 0x1p-40)
      XCTAssertLessThanOrEqual(
        error, bound, "\(x)^\(n): \(computed), relative error \(error)")
    }
  }

  /// Float: xⁿ rounded once from Double, so within half a Float ulp and
  /// 2n·2⁻⁵³ relative of xⁿ.
  func testFloat_WithinHalfAnUlp() {
    for (x, n) in cases(seed: 4) {
      let xFloat = Float(x)
      let exact = DoubleDouble.pow(DoubleDouble(Double(xFloat)), n)
      guard exact.hi >= Double(Float.leastNormalMagnitude) else { continue }
      let computed = specularPower(xFloat, Float(n))
      let error = (DoubleDouble(Double(computed)) - exact).hi.magnitude
      let bound =
        Double(Float(exact.hi).ulp) / 2 + 2 * Double(n) * 0x1p-53
        * exact.hi * (1 + 0x1p-40)
      XCTAssertLessThanOrEqual(
        error, bound, "\(xFloat)^\(n): \(computed), error \(error)")
    }
  }

  /// Shininesses that are not whole numbers from 2 to 1024 get `pow`'s
  /// own bits.
  func testOtherShininesses_ThePowOfTheCLibrary() {
    let xs: [Double] = [0.3, 0.75, 0.999, 1, 1 + 4 * .ulpOfOne]
    let shininesses: [Double] = [
      1.5, 2.5, 10.25, 1025, 2048, 1e6, -2, 0.5, .nan, .infinity,
    ]
    for x in xs {
      for y in shininesses {
        XCTAssertEqual(
          specularPower(x, y).bitPattern, Double.pow(x, y).bitPattern,
          "\(x)^\(y)")
        XCTAssertEqual(
          specularPower(Float(x), Float(y)).bitPattern,
          Float.pow(Float(x), Float(y)).bitPattern, "\(x)^\(y) in Float")
      }
    }
  }

  /// The shading formula with it: a black specular colour and shininess
  /// 0 and 1 take the same shortcuts as with `pow` (the same bits), and a
  /// shiny material's colour moves by little more than the power's bound.
  func testShading_AsWithPowWithinTheBound() {
    let light = Light<Double>.directional(
      direction: Vector3(0.3, -1, -0.2).normalized(),
      color: Vector3(0.9, 0.8, 0.7))
    var generator = SplitMix64(seed: 9)
    func unit() -> Vector3<Double> {
      Vector3(
        Double(generator.next() % 2001) / 1000 - 1,
        Double(generator.next() % 2001) / 1000 - 1,
        Double(generator.next() % 2001) / 1000 - 1
      ).normalized()
    }
    for shininess in [0.0, 1, 2, 20, 40, 100, 1024] {
      for specular in [RGB<Double>.zero, RGB(0.9, 0.6, 0.3)] {
        let surface = Material<Double>.Surface(
          diffuse: RGB(0.5, 0.4, 0.3), specular: specular,
          shininess: shininess)
        for _ in 0..<200 {
          let (normal, view) = (unit(), unit())
          func shaded(_ power: (Double, Double) -> Double) -> RGB<Double> {
            surface.shade(
              point: .zero, normal: normal, viewDirection: view,
              ambient: RGB(0.1, 0.1, 0.1), lights: [light],
              attenuate: false, power: power)
          }
          let withPow = shaded(Double.pow)
          let withSquares = shaded(specularPower)
          if shininess <= 1 || specular == .zero {
            XCTAssertEqual(withSquares, withPow)
          } else {
            // The power's 2n·2⁻⁵³ and `pow`'s ulp, times colours ≤ 1,
            // and a few roundings of sums below 2.
            let difference = (withSquares - withPow).maxMagnitude
            XCTAssertLessThanOrEqual(
              difference, (2 * shininess + 4) * 0x1p-52)
          }
        }
      }
    }
  }
}
