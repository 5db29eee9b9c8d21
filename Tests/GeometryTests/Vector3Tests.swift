import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

final class Vector3Tests: XCTestCase {
  /// Every operation on small integers and halves is exact.
  func checkArithmetic<T: RayScalar>(_: T.Type) {
    let a = Vector3<T>(1, -2, 3)
    let b = Vector3<T>(0.5, 4, -1)
    XCTAssertEqual(a + b, Vector3(1.5, 2, 2))
    XCTAssertEqual(a - b, Vector3(0.5, -6, 4))
    XCTAssertEqual(-a, Vector3(-1, 2, -3))
    XCTAssertEqual(a * 2, Vector3(2, -4, 6))
    XCTAssertEqual(2 * a, a * 2)
    XCTAssertEqual(a * b, Vector3(0.5, -8, -3), "component-wise")
    XCTAssertEqual(a / 4, Vector3(0.25, -0.5, 0.75))
    var c = a
    c += b
    XCTAssertEqual(c, a + b)
    XCTAssertEqual(a.dot(b), 0.5 - 8 - 3)
    XCTAssertEqual(Vector3<T>.zero, Vector3(0, 0, 0))
    XCTAssertEqual(Vector3<T>(3, 4, 12).lengthSquared, 169)
    XCTAssertEqual(Vector3<T>(3, 4, 12).length, 13)
    XCTAssertEqual(Vector3<T>(3, -7, 5).maxMagnitude, 7)
    XCTAssertEqual([a[0], a[1], a[2]], [1, -2, 3])
    XCTAssertEqual(
      Vector3<T>(-0.5, 0.5, 1.5).clampedToUnit(), Vector3(0, 0.5, 1))
  }

  func testArithmetic_Float() { checkArithmetic(Float.self) }
  func testArithmetic_Double() { checkArithmetic(Double.self) }

  /// x × y = z and its cyclic permutations (a right-handed basis); the
  /// cross product is anticommutative, perpendicular to both factors, and
  /// zero for parallel vectors.
  func checkCross<T: RayScalar>(_: T.Type) {
    let x = Vector3<T>(1, 0, 0)
    let y = Vector3<T>(0, 1, 0)
    let z = Vector3<T>(0, 0, 1)
    XCTAssertEqual(x.cross(y), z)
    XCTAssertEqual(y.cross(z), x)
    XCTAssertEqual(z.cross(x), y)
    XCTAssertEqual(y.cross(x), -z)
    let a = Vector3<T>(2, -3, 5)
    let b = Vector3<T>(-1, 4, 0.5)
    XCTAssertEqual(a.cross(b), Vector3(-21.5, -6, 5), "exact: small halves")
    XCTAssertEqual(a.cross(b), -b.cross(a))
    XCTAssertEqual(a.cross(b).dot(a), 0)
    XCTAssertEqual(a.cross(b).dot(b), 0)
    XCTAssertEqual(a.cross(a * 3), .zero)
  }

  func testCross_Float() { checkCross(Float.self) }
  func testCross_Double() { checkCross(Double.self) }

  /// Unit length, same direction, at every scale the type has: the squared
  /// length overflows above √max and underflows below √min, where
  /// `normalized` rescales first.
  func checkNormalizedScales<T: RayScalar>(_: T.Type, base: UInt64) {
    let epsilon = Double(T.ulpOfOne)
    // Fixed extremes: overflowing, underflowing, subnormal components.
    let extremes: [Vector3<T>] = [
      Vector3(T.greatestFiniteMagnitude, T.greatestFiniteMagnitude, 0),
      Vector3(
        T.greatestFiniteMagnitude, -T.greatestFiniteMagnitude,
        T.greatestFiniteMagnitude),
      Vector3(T.leastNonzeroMagnitude, 0, 0),
      Vector3(0, -T.leastNonzeroMagnitude, T.leastNonzeroMagnitude),
      Vector3(T.leastNormalMagnitude, T.leastNormalMagnitude, 0),
      Vector3(T.greatestFiniteMagnitude, T.leastNonzeroMagnitude, 0),
    ]
    for vector in extremes {
      let unit = vector.normalized()
      // The reference scales by 2^−exponent of the largest component
      // (exact) before squaring in the wider type; component by component,
      // since 2^1074 itself overflows a reference with Double's exponent
      // range (DoubleDouble, where there is no Float80).
      let shift = -ReferenceScalar(vector.maxMagnitude).exponent
      func scaled(_ c: ReferenceScalar) -> ReferenceScalar {
        c == 0
          ? c
          : ReferenceScalar(
            sign: c.sign, exponent: c.exponent + shift,
            significand: c.significand)
      }
      let reference = vector.reference
      let scaled = Vector3(
        scaled(reference.x), scaled(reference.y), scaled(reference.z))
      let want = scaled / scaled.length
      assertRelativeError(unit, want, ulps: 2, "\(T.self) \(vector)")
    }
    forEachSeed(2000, base: base) { generator, seed in
      let logMax =
        Double.log(Double(T.greatestFiniteMagnitude)) / Double.log(10)
      let logMin = Double.log(Double(T.leastNormalMagnitude)) / Double.log(10)
      let magnitude = T(
        Double.pow(10, Double.random(in: logMin...logMax, using: &generator)))
      let vector = generator.unitVector(T.self) * magnitude
      guard vector.maxMagnitude > 0 && vector.isFinite else { return }
      let unit = vector.normalized()
      // Division by √(x² + y² + z²): the sum, the root and the quotient,
      // or the same after an exact-ish rescale. Measured worst 1.5 ulps
      // of the largest component; budget 2. |n| − 1 within 2ε likewise.
      let scale = ReferenceScalar(
        sign: .plus, exponent: -ReferenceScalar(vector.maxMagnitude).exponent,
        significand: 1)
      let scaled = vector.reference * scale
      assertRelativeError(
        unit, scaled / scaled.length, ulps: 2,
        "seed \(seed) magnitude \(magnitude)")
      XCTAssertEqual(
        Double(unit.length), 1, accuracy: 2 * epsilon,
        "seed \(seed) magnitude \(magnitude)")
    }
  }

  func testNormalized_AllScales_Float() {
    checkNormalizedScales(Float.self, base: 0x7EC7_0001)
  }
  func testNormalized_AllScales_Double() {
    checkNormalizedScales(Double.self, base: 0x7EC7_0002)
  }

  /// Documented: a zero vector has no direction and gives NaNs.
  func testNormalized_ZeroGivesNaN() {
    let unit = Vector3<Double>.zero.normalized()
    XCTAssertTrue(unit.x.isNaN && unit.y.isNaN && unit.z.isNaN)
    XCTAssertFalse(unit.isFinite)
  }

  func testIsFinite() {
    XCTAssertTrue(Vector3<Double>(1, -1e300, 0).isFinite)
    XCTAssertFalse(Vector3<Double>(1, .infinity, 0).isFinite)
    XCTAssertFalse(Vector3<Double>(1, 0, -.infinity).isFinite)
    XCTAssertFalse(Vector3<Double>(.nan, 0, 0).isFinite)
  }

  /// Converting rounds each component to nearest.
  func testInit_ConvertsPrecision() {
    let double = Vector3<Double>(0.1, 1e39, -1e-50)
    let float = Vector3<Float>(double)
    XCTAssertEqual(float.x, Float(0.1))
    XCTAssertEqual(float.y, .infinity)
    XCTAssertEqual(float.z, -0.0)
    XCTAssertEqual(float.z.sign, .minus)
    XCTAssertEqual(
      Vector3<Double>(Vector3<Float>(0.5, 2, -3)), Vector3(0.5, 2, -3))
  }

  func testDescription() {
    XCTAssertEqual(Vector3<Double>(1, -2.5, 0).description, "(1.0, -2.5, 0.0)")
  }

  func testHashable() {
    let set: Set = [
      Vector3<Double>(1, 2, 3), Vector3(1, 2, 3), Vector3(3, 2, 1),
    ]
    XCTAssertEqual(set.count, 2)
  }
}
