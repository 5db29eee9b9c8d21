import XCTest

@testable import ExactArithmetic
@testable import FastEngine
@testable import FastKernels
@testable import Geometry
import TestSupport

/// The camera-relative records (`CameraRelative`): compensated offsets
/// from the eye, rounded once.
final class CameraRelativeTests: XCTestCase {
  /// The exact integer checks use Int128, which macOS has from 15 on.
  static let int128 = "Int128 needs macOS 15; Linux always has it"

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
