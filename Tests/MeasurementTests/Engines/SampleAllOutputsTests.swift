import Course
import FastEngine
import Geometry
import SceneDescription
import SceneIO
import XCTest

/// `--sample-all-outputs`: depth and normals the means of each pixel's
/// samples, as defined in docs/CONVENTIONS.md ("Supersampling") and
/// computed here from that definition with the course's `Sphere`: the
/// depth over the samples that hit (∞ when none does), the normal the sum
/// of the samples' normals (a miss adding zero) over their number.
final class SampleAllOutputsTests: XCTestCase {
  let size = (width: 40, height: 30)

  func settings(_ outputs: RenderOutputs) -> RenderSettings {
    var settings = RenderSettings(
      width: size.width, height: size.height, outputs: outputs, threads: 2)
    settings.samples = 9
    settings.samplesAllOutputs = true
    return settings
  }

  /// The scene's one sphere, and per pixel the definition's depth, normal
  /// and number of samples that hit.
  func expected(_ scene: Scene) throws -> [(
    depth: Double, normal: Vector3<Double>, hits: Int
  )] {
    guard case .sphere(let described) = scene.root.objects.first else {
      throw XCTSkip("the scene's one object is a sphere")
    }
    let sphere = Sphere(center: described.center, radius: described.radius)
    let settings = settings([.depth, .normals])
    let camera = settings.camera(scene.camera, as: Double.self)
    var pixels: [(depth: Double, normal: Vector3<Double>, hits: Int)] = []
    for row in 0..<size.height {
      for column in 0..<size.width {
        var samples = PixelSamples(
          column: column, row: row, camera: camera, settings: settings)
        var (depth, normal, hits) = (0.0, Vector3<Double>.zero, 0)
        while let direction = samples.next() {
          let ray = Ray(origin: camera.center, direction: direction)
          guard let hit = sphere.intersect(ray, after: 0, before: .infinity)
          else { continue }
          (depth, normal, hits) = (depth + hit.t, normal + hit.normal, hits + 1)
        }
        pixels.append(
          (
            hits > 0 ? depth / Double(hits) : .infinity,
            normal / Double(samples.count), hits
          ))
      }
    }
    return pixels
  }

  func sphereScene() throws -> Scene {
    try SceneReader.read(
      contentsOf: "\(projectFolder)/scenes/single-sphere.txt",
      options: SceneOptions(style: .course))
  }

  /// The course engine computes the definition itself: the same numbers.
  func testCourseEngine_IsTheDefinition() throws {
    let scene = try sphereScene()
    let expected = try expected(scene)
    let buffers = CourseEngine.render(
      scene, settings: settings([.depth, .normals]))
    var partial = 0
    for (pixel, want) in expected.enumerated() {
      XCTAssertEqual(buffers.depth[pixel], want.depth, "pixel \(pixel)")
      XCTAssertEqual(buffers.normals[pixel], want.normal, "pixel \(pixel)")
      if want.hits > 0 && want.hits < 9 { partial += 1 }
    }
    // The silhouette crosses pixels: averaging is exercised, a miss
    // weighing the normal down.
    XCTAssertGreaterThan(partial, size.width / 2)
  }

  /// The fast engine, in Double and in Float, against the definition
  /// where both agree on which samples hit (the normal's length, the share
  /// of samples hit, tells): depth within the engines' agreement bound
  /// (`EngineAgreementTests.depthBound`, relative) in Double and 2⁻²⁰
  /// (8 ε of Float: a few roundings of t and of the mean) in Float, and
  /// the normals within the same bound, absolute (unit vectors).
  func testFastEngine_IsTheDefinition() throws {
    let scene = try sphereScene()
    let expected = try expected(scene)
    let settings = settings([.depth, .normals])
    func check(_ buffers: RenderBuffers<Double>, bound: Double) {
      var compared = 0
      for (pixel, want) in expected.enumerated() {
        let normal = buffers.normals[pixel]
        let coverage = Double(want.hits) / 9
        // A sample that hit in one and missed in the other changes the
        // normal's length by about 1/9.
        guard abs(normal.length - coverage) < 0.05 else { continue }
        compared += 1
        if want.hits == 0 {
          XCTAssertEqual(buffers.depth[pixel], .infinity, "pixel \(pixel)")
          XCTAssertEqual(normal, .zero, "pixel \(pixel)")
          continue
        }
        XCTAssertEqual(
          buffers.depth[pixel], want.depth, accuracy: bound * want.depth,
          "pixel \(pixel)")
        XCTAssertLessThanOrEqual(
          (normal - want.normal).length, bound, "pixel \(pixel)")
      }
      XCTAssertGreaterThanOrEqual(compared, expected.count * 99 / 100)
    }
    check(
      Renderer.render(
        CompiledScene<StableKernel<Double>>(scene), settings: settings),
      bound: EngineAgreementTests.depthBound)
    check(
      AnyRenderBuffers(
        Renderer.render(
          CompiledScene<StableKernel<Float>>(scene), settings: settings)
      ).doubles, bound: 0x1p-20)
  }

  /// The shaded image is the same with and without every output sampled,
  /// in both engines; at one sample a pixel the flag changes nothing.
  func testShadedImage_Unchanged() throws {
    let scene = try SceneReader.read(
      contentsOf: "\(projectFolder)/scenes/spheres.txt",
      options: SceneOptions(style: .course))
    var all = settings([.depth, .normals, .shaded])
    var centre = all
    centre.samplesAllOutputs = false
    XCTAssertEqual(
      CourseEngine.render(scene, settings: all).color,
      CourseEngine.render(scene, settings: centre).color)
    let compiled = CompiledScene<StableKernel<Double>>(scene)
    XCTAssertEqual(
      Renderer.render(compiled, settings: all).color,
      Renderer.render(compiled, settings: centre).color)
    (all.samples, centre.samples) = (1, 1)
    let one = CourseEngine.render(scene, settings: all)
    let plain = CourseEngine.render(scene, settings: centre)
    XCTAssertEqual(one.depth, plain.depth)
    XCTAssertEqual(one.normals, plain.normals)
    let fastOne = Renderer.render(compiled, settings: all)
    let fastPlain = Renderer.render(compiled, settings: centre)
    XCTAssertEqual(fastOne.depth, fastPlain.depth)
    XCTAssertEqual(fastOne.normals, fastPlain.normals)
  }
}
