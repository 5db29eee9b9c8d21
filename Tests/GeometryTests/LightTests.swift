import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

final class LightTests: XCTestCase {
  /// A directional light arrives from −direction with its full colour,
  /// wherever the point and whether or not attenuating.
  func checkDirectional<T: RayScalar>(_: T.Type) {
    let light = Light<T>.directional(
      direction: Vector3(0, -1, 0), color: Vector3(0.5, 1, 2))
    for point in [Vector3<T>.zero, Vector3(1e3, -5, 7)] {
      for attenuate in [false, true] {
        let (toLight, color) = light.illumination(
          at: point, attenuate: attenuate)
        XCTAssertEqual(toLight, Vector3(0, 1, 0), "\(T.self)")
        XCTAssertEqual(color, Vector3(0.5, 1, 2), "\(T.self)")
      }
    }
  }

  func testIllumination_Directional_Float() { checkDirectional(Float.self) }
  func testIllumination_Directional_Double() { checkDirectional(Double.self) }

  /// A point light: the unit vector towards it, and its colour divided by
  /// falloff·dist² only when attenuating with a falloff given.
  func checkPoint<T: RayScalar>(_: T.Type) {
    let position = Vector3<T>(1, 2, 3)
    let point = Vector3<T>(-2, 6, 3)  // offset (3, −4, 0), distance 5
    let colour = Vector3<T>(1, 0.5, 0.25)
    let attenuated = Light<T>.point(
      position: position, color: colour, falloff: 0.04)
    let plain = Light<T>.point(position: position, color: colour, falloff: nil)

    let (toLight, arriving) = attenuated.illumination(
      at: point, attenuate: true)
    // (3, −4, 0)/5: one rounding per component.
    assertRelativeError(
      toLight, Vector3(0.6, -0.8, 0), ulps: 1, "\(T.self) toLight")
    // colour / (0.04·25): 0.04 is rounded, then the product and quotient.
    assertRelativeError(
      arriving, colour.reference, ulps: 2, "\(T.self) 1/(0.04·25) = 1")

    // Distance 10: colour / (0.04·100) = colour / 4.
    let far = Vector3<T>(1, 2, 13)
    let (_, dimmer) = attenuated.illumination(at: far, attenuate: true)
    assertRelativeError(
      dimmer, (colour / 4).reference, ulps: 2, "\(T.self) inverse square law")

    XCTAssertEqual(
      attenuated.illumination(at: point, attenuate: false).color, colour)
    XCTAssertEqual(plain.illumination(at: point, attenuate: true).color, colour)
    XCTAssertEqual(
      plain.illumination(at: point, attenuate: false).color, colour)
    XCTAssertEqual(
      plain.illumination(at: point, attenuate: true).toLight,
      attenuated.illumination(at: point, attenuate: true).toLight)
  }

  func testIllumination_Point_Float() { checkPoint(Float.self) }
  func testIllumination_Point_Double() { checkPoint(Double.self) }

  /// The direction to a point light stays unit length at any scale, even
  /// where the squared distance overflows or underflows.
  func checkPointScales<T: RayScalar>(_: T.Type) {
    let big = T.greatestFiniteMagnitude.squareRoot() * 4
    let small = T.leastNormalMagnitude.squareRoot() / 4
    for scale in [small, 1, big] {
      let light = Light<T>.point(
        position: Vector3(3, 4, 0) * scale, color: Vector3(1, 1, 1),
        falloff: nil)
      let (toLight, _) = light.illumination(at: .zero, attenuate: false)
      // Scaled before normalising when |offset|² is not normal: a few
      // roundings more than the direct path.
      assertRelativeError(
        toLight, Vector3(0.6, 0.8, 0), ulps: 2, "\(T.self) scale \(scale)")
    }
  }

  func testIllumination_PointAtExtremeScales_Float() {
    checkPointScales(Float.self)
  }
  func testIllumination_PointAtExtremeScales_Double() {
    checkPointScales(Double.self)
  }

  func testInit_ConvertsPrecision() {
    let point = Light<Float>(
      Light<Double>.point(
        position: Vector3(0.1, 0.2, 0.3), color: Vector3(0.4, 0.5, 0.6),
        falloff: 0.7))
    XCTAssertEqual(
      point,
      .point(
        position: Vector3(0.1, 0.2, 0.3), color: Vector3(0.4, 0.5, 0.6),
        falloff: 0.7))
    let noFalloff = Light<Float>(
      Light<Double>.point(
        position: .zero, color: Vector3(1, 1, 1), falloff: nil))
    XCTAssertEqual(
      noFalloff, .point(position: .zero, color: Vector3(1, 1, 1), falloff: nil))
    let directional = Light<Float>(
      Light<Double>.directional(
        direction: Vector3(0.6, -0.8, 0), color: Vector3(1, 1, 1)))
    XCTAssertEqual(
      directional,
      .directional(direction: Vector3(0.6, -0.8, 0), color: Vector3(1, 1, 1)))
  }
}
