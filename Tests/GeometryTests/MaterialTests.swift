import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

final class MaterialTests: XCTestCase {
  /// ambient·kd + Σ lights [kd·max(0, n·l) + ks·max(0, −d·r)^s]·light, with
  /// r = 2(n·l)n − l and the specular term only where n·l > 0, written out
  /// independently in ReferenceScalar from T's values.
  func referenceShade<T: RayScalar>(
    _ material: Material<T>, point: Vector3<T>, normal: Vector3<T>,
    view: Vector3<T>, ambient: RGB<T>, lights: [Light<T>], attenuate: Bool
  ) -> (color: RGB<ReferenceScalar>, scale: RGB<ReferenceScalar>) {
    typealias R = ReferenceScalar
    let kd = material.diffuse.reference
    let ks = material.specular.reference
    let n = normal.reference
    var color = ambient.reference * kd
    // The sum of the magnitudes of every term, per channel: what the
    // rounding errors scale with.
    var scale = color
    for light in lights {
      let toLight: Vector3<R>
      var lightColor: RGB<R>
      switch light {
      case .directional(let direction, let rgb):
        toLight = -direction.reference
        lightColor = rgb.reference
      case .point(let position, let rgb, let falloff):
        let offset = position.reference - point.reference
        toLight = offset / offset.length
        lightColor = rgb.reference
        if attenuate, let falloff {
          lightColor = lightColor / (R(falloff) * offset.lengthSquared)
        }
      }
      let cosine = n.dot(toLight)
      guard cosine > 0 else { continue }
      var term = kd * cosine
      let reflected = n * (2 * cosine) - toLight
      let highlight = -view.reference.dot(reflected)
      if highlight > 0 {
        term += ks * R.pow(highlight, R(material.shininess))
      }
      color += term * lightColor
      scale += term * lightColor
    }
    return (color, scale)
  }

  /// No lights: only the ambient term, ambient·kd, exact for these values.
  func checkAmbientOnly<T: RayScalar>(_: T.Type) {
    let material = Material<T>(
      diffuse: Vector3(0.5, 1, 0.25), specular: Vector3(1, 1, 1), shininess: 8)
    let color = material.surface.shade(
      point: .zero, normal: Vector3(0, 1, 0), viewDirection: Vector3(0, -1, 0),
      ambient: Vector3(0.5, 0.25, 1), lights: [], attenuate: true)
    XCTAssertEqual(color, Vector3(0.25, 0.25, 0.25), "\(T.self)")
  }

  func testShade_AmbientOnly_Float() { checkAmbientOnly(Float.self) }
  func testShade_AmbientOnly_Double() { checkAmbientOnly(Double.self) }

  /// Light straight down on an upward normal, seen straight down: n·l = 1
  /// and −d·r = 1, so the colour is ambient·kd + (kd + ks)·light exactly.
  func checkHeadOn<T: RayScalar>(_: T.Type) {
    let material = Material<T>(
      diffuse: Vector3(0.5, 0.25, 0.125), specular: Vector3(0.25, 0.25, 0.5),
      shininess: 30)
    let light = Light<T>.directional(
      direction: Vector3(0, -1, 0), color: Vector3(1, 0.5, 2))
    let color = material.surface.shade(
      point: Vector3(3, 0, 4), normal: Vector3(0, 1, 0),
      viewDirection: Vector3(0, -1, 0),
      ambient: Vector3(0.5, 0.5, 0.5), lights: [light], attenuate: false)
    // (0.25, 0.125, 0.0625) + (0.75, 0.5, 0.625)·(1, 0.5, 2), all dyadic.
    XCTAssertEqual(color, Vector3(1, 0.375, 1.3125), "\(T.self)")
  }

  func testShade_HeadOn_Float() { checkHeadOn(Float.self) }
  func testShade_HeadOn_Double() { checkHeadOn(Double.self) }

  /// l = (0.6, 0.8, 0) on n = +y: n·l = 0.8, r = (−0.6, 0.8, 0). Seen along
  /// the mirror direction the highlight is 1; seen straight down, 0.8^s.
  func checkOblique<T: RayScalar>(_: T.Type) {
    let material = Material<T>(
      diffuse: Vector3(1, 0.5, 0), specular: Vector3(0, 0.5, 1), shininess: 10)
    let light = Light<T>.directional(
      direction: Vector3(-0.6, -0.8, 0), color: Vector3(1, 1, 1))
    let normal = Vector3<T>(0, 1, 0)
    let cases: [(view: Vector3<T>, highlight: ReferenceScalar)] = [
      (Vector3(0.6, -0.8, 0), 1),
      (Vector3(0, -1, 0), 0.8),
      (Vector3(-0.6, -0.8, 0), 0.28),  // −d·r = −0.36 + 0.64
    ]
    for (view, highlight) in cases {
      let color = material.surface.shade(
        point: .zero, normal: normal, viewDirection: view, ambient: .zero,
        lights: [light], attenuate: false)
      let specular = ReferenceScalar.pow(highlight, 10)
      let want = Vector3<ReferenceScalar>(0.8, 0.4 + 0.5 * specular, specular)
      // n·l, r and −d·r each carry a few roundings of 0.6 and 0.8 (all
      // below an ulp here), and the tenth power multiplies the
      // highlight's relative error by 10: budget 4 ulps of the largest
      // component; measured worst 0.33 (Double), 0.2 (Float).
      assertRelativeError(color, want, ulps: 4, "\(T.self) view \(view)")
    }
  }

  func testShade_Oblique_Float() { checkOblique(Float.self) }
  func testShade_Oblique_Double() { checkOblique(Double.self) }

  /// A light below the surface contributes nothing, not even a highlight
  /// that −d·r > 0 would otherwise allow; a light exactly in the tangent
  /// plane (n·l = 0) contributes nothing either.
  func checkLightBehind<T: RayScalar>(_: T.Type) {
    let material = Material<T>(
      diffuse: Vector3(1, 1, 1), specular: Vector3(1, 1, 1), shininess: 1)
    // toLight = (0, 0.6, −0.8): n·l = −0.8, r = (0, −0.6, −0.8), and with
    // d = (0, 0.6, 0.8) the highlight −d·r would be 1.
    let below = Light<T>.directional(
      direction: Vector3(0, -0.6, 0.8), color: Vector3(1, 1, 1))
    let tangent = Light<T>.directional(
      direction: Vector3(-1, 0, 0), color: Vector3(1, 1, 1))
    let ambient = Vector3<T>(0.25, 0.5, 0.75)
    let color = material.surface.shade(
      point: .zero, normal: Vector3(0, 0, 1),
      viewDirection: Vector3(0, 0.6, 0.8),
      ambient: ambient, lights: [below, tangent], attenuate: false)
    XCTAssertEqual(color, ambient, "\(T.self): only the ambient term")
  }

  func testShade_LightBehindOrTangent_Float() { checkLightBehind(Float.self) }
  func testShade_LightBehindOrTangent_Double() { checkLightBehind(Double.self) }

  /// Shininess 0 makes the highlight x^0 = 1 wherever −d·r > 0, and none
  /// where −d·r ≤ 0: max(0, −d·r)^0 is taken as 0 there, not as pow's
  /// 0^0 = 1, so that a surface never shows a highlight facing away from
  /// the reflection.
  func checkShininessZero<T: RayScalar>(_: T.Type) {
    let material = Material<T>(diffuse: .zero, specular: Vector3(0.5, 0.25, 1))
    XCTAssertEqual(material.shininess, 0)
    let light = Light<T>.directional(
      direction: Vector3(0, -1, 0), color: Vector3(1, 1, 1))
    let normal = Vector3<T>(0, 1, 0)
    // r = (0, 1, 0); d = (0.6, −0.8, 0) gives −d·r = 0.8 > 0.
    let lit = material.surface.shade(
      point: .zero, normal: normal, viewDirection: Vector3(0.6, -0.8, 0),
      ambient: .zero, lights: [light], attenuate: false)
    XCTAssertEqual(lit, Vector3(0.5, 0.25, 1), "\(T.self)")
    // d = (0, 1, 0) looks away from the reflection: −d·r = −1.
    let unlit = material.surface.shade(
      point: .zero, normal: normal, viewDirection: Vector3(0, 1, 0),
      ambient: .zero, lights: [light], attenuate: false)
    XCTAssertEqual(unlit, .zero, "\(T.self)")
    // d = (1, 0, 0) is perpendicular to r: −d·r = 0 exactly.
    let perpendicular = material.surface.shade(
      point: .zero, normal: normal, viewDirection: Vector3(1, 0, 0),
      ambient: .zero, lights: [light], attenuate: false)
    XCTAssertEqual(perpendicular, .zero, "\(T.self)")
  }

  func testShade_ShininessZero_Float() { checkShininessZero(Float.self) }
  func testShade_ShininessZero_Double() { checkShininessZero(Double.self) }

  /// A point light at distance 2 straight above: the colour is divided by
  /// falloff·dist² = 0.5·4 only when attenuating and a falloff is given.
  func checkPointLightAttenuation<T: RayScalar>(_: T.Type) {
    let material = Material<T>(diffuse: Vector3(1, 0.5, 0.25))
    let normal = Vector3<T>(0, 0, 1)
    let point = Vector3<T>(1, 2, 3)
    let withFalloff = Light<T>.point(
      position: Vector3(1, 2, 5), color: Vector3(1, 1, 1), falloff: 0.5)
    let withoutFalloff = Light<T>.point(
      position: Vector3(1, 2, 5), color: Vector3(1, 1, 1), falloff: nil)
    func shade(_ light: Light<T>, attenuate: Bool) -> RGB<T> {
      material.surface.shade(
        point: point, normal: normal, viewDirection: Vector3(0, 0, -1),
        ambient: .zero,
        lights: [light], attenuate: attenuate)
    }
    XCTAssertEqual(
      shade(withFalloff, attenuate: true), Vector3(0.5, 0.25, 0.125))
    XCTAssertEqual(shade(withFalloff, attenuate: false), Vector3(1, 0.5, 0.25))
    XCTAssertEqual(
      shade(withoutFalloff, attenuate: true), Vector3(1, 0.5, 0.25))
    XCTAssertEqual(
      shade(withoutFalloff, attenuate: false), Vector3(1, 0.5, 0.25))
  }

  func testShade_PointLightAttenuation_Float() {
    checkPointLightAttenuation(Float.self)
  }
  func testShade_PointLightAttenuation_Double() {
    checkPointLightAttenuation(Double.self)
  }

  /// Random materials, geometry and up to four lights of both kinds,
  /// against the reference. Rounding errors scale with the sum of the
  /// magnitudes of the terms; the power s multiplies the highlight's
  /// relative error by s. Budget per channel: 8·(1 + s)·ε·Σ|terms|;
  /// measured worst 0.37 of that (Float and Double).
  func checkRandom<T: RayScalar>(_: T.Type, base: UInt64) {
    var worst = 0.0
    forEachSeed(2000, base: base) { generator, seed in
      func color() -> RGB<T> {
        Vector3(
          generator.uniform(0...1), generator.uniform(0...1),
          generator.uniform(0...1))
      }
      let material = Material(
        diffuse: color(), specular: color(),
        shininess: Bool.random(using: &generator)
          ? 0 : generator.logUniform(0.5, 100))
      let normal = generator.unitVector(T.self)
      let point = generator.unitVector(T.self) * generator.logUniform(0.1, 10)
      let view = generator.unitVector(T.self)
      let attenuate = Bool.random(using: &generator)
      var lights: [Light<T>] = []
      for _ in 0..<Int.random(in: 0...4, using: &generator) {
        if Bool.random(using: &generator) {
          lights.append(
            .directional(
              direction: generator.unitVector(T.self), color: color()))
        } else {
          let position =
            point
            + generator.unitVector(T.self) * generator.logUniform(0.5, 20)
          let falloff: T? =
            Bool.random(using: &generator) ? generator.logUniform(0.01, 1) : nil
          lights.append(
            .point(position: position, color: color(), falloff: falloff))
        }
      }
      let ambient = color()
      let got = material.surface.shade(
        point: point, normal: normal, viewDirection: view, ambient: ambient,
        lights: lights, attenuate: attenuate)
      let (want, scale) = referenceShade(
        material, point: point, normal: normal, view: view, ambient: ambient,
        lights: lights, attenuate: attenuate)
      let unit =
        8 * (1 + ReferenceScalar(material.shininess))
        * ReferenceScalar(T.ulpOfOne)
      for axis in 0..<3 {
        let error = (ReferenceScalar(got[axis]) - want[axis]).magnitude
        let allowed = unit * scale[axis]
        if allowed > 0 { worst = max(worst, Double(error / allowed)) }
        XCTAssertLessThanOrEqual(
          error, allowed,
          "seed \(seed) channel \(axis): \(got[axis]) vs \(want[axis])")
      }
    }
    print("\(T.self) shade worst: \(worst) of the budget")
  }

  func testShade_Random_Float() { checkRandom(Float.self, base: 0x5AAD_0001) }
  func testShade_Random_Double() { checkRandom(Double.self, base: 0x5AAD_0002) }

  func testDefaultWhite() {
    let white = Material<Double>.defaultWhite
    XCTAssertEqual(white.diffuse, Vector3(1, 1, 1))
    XCTAssertEqual(white.specular, .zero)
    XCTAssertEqual(white.shininess, 0)
  }

  func testInit_ConvertsPrecision() {
    let double = Material<Double>(
      diffuse: Vector3(0.1, 0.2, 0.3), specular: Vector3(0.4, 0.5, 0.6),
      shininess: 12.5)
    let float = Material<Float>(double)
    XCTAssertEqual(float.diffuse, Vector3(0.1, 0.2, 0.3))
    XCTAssertEqual(float.specular, Vector3(0.4, 0.5, 0.6))
    XCTAssertEqual(float.shininess, 12.5)
  }
}
