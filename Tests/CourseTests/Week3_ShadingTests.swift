import Geometry
import SceneDescription
import XCTest

@testable import Course

/// Week 3, shading: the colour along a ray (`View.color`). The background
/// where it misses; else the hit's material lit by the ambient light and
/// every light, Phong's ambient·kd + Σ [kd·max(0, n·l) + ks·max(0, −d·r)ˢ]
/// ·light (r = 2(n·l)n − l; `Material.shade`, given), a textured
/// material's kd being the texel at the hit's texture coordinates.
///
/// The colours, lights and angles below are chosen so that every product
/// and sum is exact in Double, or one rounding away: any correct shading
/// gives each channel within 4 ε of its value, relative to the colour.
final class Week3_ShadingTests: XCTestCase {
  let kd = RGB<Double>(0.5, 0.25, 1)
  let ambient = RGB<Double>(0.25, 0.5, 0.125)
  let background = RGB<Double>(0.1, 0.2, 0.3)
  let light = RGB<Double>(1, 0.5, 0.25)
  static let exact = "sums and products of these binary fractions allow"

  /// A sphere of radius 2 at (0, 0, −10) seen from the origin: the ray down
  /// −z hits it at (0, 0, −8), where its normal is (0, 0, 1).
  func view(
    _ lights: [Light<Double>], material: Material<Double>? = nil,
    style: ImageStyle = .course, textures: [Texture?] = []
  ) throws -> View {
    let camera = try XCTUnwrap(
      PerspectiveCamera(
        center: .zero, direction: Vector3(0, 0, -1), up: Vector3(0, 1, 0),
        angle: 30))
    let sphere = SceneDescription.Sphere(
      center: Vector3<Double>(0, 0, -10), radius: 2)
    let scene = Scene(
      camera: camera, lights: lights, background: background,
      ambient: ambient, materials: [material ?? Material(diffuse: kd)],
      root: SceneDescription.Group([.sphere(sphere)]))
    return View(
      scene, textures: textures,
      settings: RenderSettings(
        width: 8, height: 8, outputs: [.shaded], style: style))
  }

  /// The colour the course draws along `ray`: its nearest hit, shaded.
  func color(
    _ view: View,
    _ ray: Ray<Double> = Ray(origin: .zero, direction: Vector3(0, 0, -1))
  ) -> RGB<Double> {
    view.color(ray, view.world.intersect(ray, after: 0, before: .infinity))
  }

  /// A light shining down −z, onto the sphere's front.
  var headOn: Light<Double> {
    .directional(direction: Vector3(0, 0, -1), color: light)
  }

  func testMiss_TheBackground() throws {
    let view = try view([headOn])
    XCTAssertEqual(
      color(view, Ray(origin: .zero, direction: Vector3(0, 1, 0))),
      background)
  }

  /// n·l = 1: ambient·kd + kd·light.
  func testDiffuse_LitHeadOn() throws {
    assertClose(
      color(try view([headOn])), ambient * kd + kd * light, epsilons: 4,
      Self.exact)
  }

  /// A light behind the surface (n·l < 0) adds nothing: ambient only,
  /// whether it is directional or a point behind the sphere.
  func testDiffuse_LightBehindTheSurface_AmbientOnly() throws {
    let behind: [Light<Double>] = [
      .directional(direction: Vector3(0, 0, 1), color: light),
      .point(position: Vector3(0, 0, -20), color: light, falloff: nil),
    ]
    for source in behind {
      assertClose(
        color(try view([source])), ambient * kd, epsilons: 4,
        "\(source): " + Self.exact)
    }
  }

  /// A point light at (0, 4, −5), seen from the hit (0, 0, −8) along
  /// (0, 4, 3)/5: n·l = 0.6 (the normalisation rounds each component
  /// once, so n·l within ε of 0.6).
  func testDiffuse_Oblique_TheCosine() throws {
    let side = Light<Double>.point(
      position: Vector3(0, 4, -5), color: light, falloff: nil)
    assertClose(
      color(try view([side])), ambient * kd + kd * light * 0.6, epsilons: 4,
      "the light's direction, rounded once, and " + Self.exact)
  }

  /// Every light adds its own term.
  func testTwoLights_Add() throws {
    let side = Light<Double>.point(
      position: Vector3(0, 4, -5), color: light, falloff: nil)
    assertClose(
      color(try view([headOn, side])),
      ambient * kd + kd * light + kd * light * 0.6, epsilons: 4,
      "the light's direction, rounded once, and " + Self.exact)
  }

  /// ks·max(0, −d·r)ˢ: seen head-on and lit head-on, r = n and the
  /// highlight is 1: ks. Lit from 60° above, n·l = ½, r = 2(n·l)n − l =
  /// (0, −√3/2, ½) and the highlight is ½: ks·¼ for s = 2.
  func testSpecular_TheHighlight() throws {
    let ks = RGB<Double>(0.5, 0.5, 0.5)
    let shiny = Material(diffuse: kd, specular: ks, shininess: 2)
    assertClose(
      color(try view([headOn], material: shiny)),
      ambient * kd + (kd + ks) * light, epsilons: 4, Self.exact)
    let above = Light<Double>.directional(
      direction: Vector3(0, -(0.75).squareRoot(), -0.5), color: light)
    assertClose(
      color(try view([above], material: shiny)),
      ambient * kd + (kd * 0.5 + ks * 0.25) * light, epsilons: 4,
      "n·l = ½ and r's z = ½ exactly, and " + Self.exact)
  }

  /// In the mit style a point light with a falloff is divided by
  /// falloff·distance² (here 0.5·4² = 8); the course style ignores it.
  func testPointLight_Falloff_MitStyleOnly() throws {
    let near = Light<Double>.point(
      position: Vector3(0, 0, -4), color: light, falloff: 0.5)
    assertClose(
      color(try view([near], style: .mit)), ambient * kd + kd * light / 8,
      epsilons: 4, Self.exact)
    assertClose(
      color(try view([near], style: .course)), ambient * kd + kd * light,
      epsilons: 4, Self.exact)
  }

  /// A textured material's kd is the texel at the hit's texture
  /// coordinates (u = 0.75 is the second texel of a 2×1 image, green); a
  /// hit without coordinates (the sphere's) keeps the material's kd.
  func testTexture_TheTexelIsTheDiffuseColour() throws {
    let texture = Texture(
      image: Image8(width: 2, height: 1, bytes: [255, 0, 0, 0, 255, 0]))
    let view = try view([headOn], textures: [texture])
    let green = RGB<Double>(0, 1, 0)
    let textured = Hit(
      t: 8, normal: Vector3(0, 0, 1), materialIndex: 0,
      textureCoordinate: TextureCoordinate(0.75, 0.5))
    assertClose(
      view.color(
        Ray(origin: .zero, direction: Vector3(0, 0, -1)), textured),
      ambient * green + green * light, epsilons: 4, Self.exact)
    assertClose(
      color(view), ambient * kd + kd * light, epsilons: 4, Self.exact)
  }
}
