import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Each project scene is kept in both formats (scenes/NAME.txt and
/// scenes/NAME.plist, the second written by Scripts/scene-to-plist.py):
/// both must render the same bytes, every output, in both precisions.
final class SceneFormatsTests: XCTestCase {
  static let scenes = [
    "single-sphere", "spheres", "spheres-only", "mesh-and-transforms",
    "textured",
  ]

  func render<S: RayScalar>(
    _ path: String, as _: S.Type
  ) throws -> RenderBuffers<S> {
    let scene = try SceneReader.read(
      contentsOf: path, options: SceneOptions(style: .course))
    let compiled = CompiledScene<StableKernel<S>>(
      scene, textures: try TextureLoader.load(for: scene))
    return Renderer.render(
      compiled,
      settings: RenderSettings(
        width: 64, height: 48, outputs: [.depth, .normals, .shaded],
        threads: 2))
  }

  func assertSameBytes<S: RayScalar>(_ name: String, as type: S.Type) throws {
    let folder = CompiledSceneTests.scenesFolder
    let text = try render("\(folder)/\(name).txt", as: type)
    let plist = try render("\(folder)/\(name).plist", as: type)
    XCTAssertEqual(
      text.depth.map { Double($0).bitPattern },
      plist.depth.map { Double($0).bitPattern },
      "\(name) \(S.self): depth")
    XCTAssertEqual(
      text.normals.flatMap { [$0.x, $0.y, $0.z] }.map { Double($0).bitPattern },
      plist.normals.flatMap { [$0.x, $0.y, $0.z] }.map {
        Double($0).bitPattern
      },
      "\(name) \(S.self): normals")
    XCTAssertEqual(
      text.color.flatMap { [$0.x, $0.y, $0.z] }.map { Double($0).bitPattern },
      plist.color.flatMap { [$0.x, $0.y, $0.z] }.map { Double($0).bitPattern },
      "\(name) \(S.self): shaded")
    XCTAssertTrue(
      text.depth.contains { $0.isFinite }, "\(name): the scene shows something")
  }

  func testTextAndPlist_SameBytes() throws {
    for name in Self.scenes {
      try assertSameBytes(name, as: Double.self)
      try assertSameBytes(name, as: Float.self)
    }
  }

  /// The textured scene's texels reach the image: without its textures
  /// the shaded image differs.
  func testTextured_TexturesChangeTheImage() throws {
    let path = "\(CompiledSceneTests.scenesFolder)/textured.txt"
    let scene = try SceneReader.read(
      contentsOf: path, options: SceneOptions(style: .course))
    let settings = RenderSettings(
      width: 64, height: 48, outputs: [.shaded], threads: 2)
    let with = Renderer.render(
      CompiledScene<StableKernel<Double>>(
        scene, textures: try TextureLoader.load(for: scene)),
      settings: settings)
    let without = Renderer.render(
      CompiledScene<StableKernel<Double>>(scene), settings: settings)
    let changed = zip(with.color, without.color).count { $0 != $1 }
    XCTAssertGreaterThan(changed, with.color.count / 10)
  }
}
