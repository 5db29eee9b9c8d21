import XCTest

@testable import RayTracer

/// The compiled scene (flattened, transforms baked into world space or
/// carried as ellipsoids, camera-relative, hierarchies, per-tile culling)
/// against the public model's own `Intersectable` path (groups and
/// transforms intersected as the scene file nests them), pixel by pixel.
final class CompiledSceneTests: XCTestCase {
  static var scenesFolder: String {
    var parts = "\(#filePath)".split(
      separator: "/", omittingEmptySubsequences: false)
    parts.removeLast(4)
    return parts.joined(separator: "/") + "/scenes"
  }

  /// The compiled scene's depth and normals are the model's, bit for bit:
  /// the same functions on the same numbers (see `CourseEngine`), here
  /// with the hierarchy thresholds of `CompiledScene`'s defaults rather
  /// than the command line's.
  func compare(_ name: String, width: Int = 48, height: Int = 36) throws {
    let scene = try SceneParser.parse(
      contentsOf: "\(Self.scenesFolder)/\(name).txt")
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals], threads: 2)
    let buffers = Renderer.render(
      CompiledScene<StableKernel<Double>>(scene), settings: settings)
    let camera = scene.camera
    let aspect = Double(height) / Double(width)
    var hits = 0
    for row in 0..<height {
      for column in 0..<width {
        let x: Double = ImageStyle.course.screenX(column: column, width: width)
        let y: Double = ImageStyle.course.screenY(row: row, height: height)
        let ray = Ray(
          origin: camera.center,
          direction: camera.rayDirection(x: x, y: y, aspect: aspect))
        let hit = scene.root.intersect(ray, after: 0, before: .infinity)
        let pixel = row * width + column
        XCTAssertEqual(
          buffers.depth[pixel], hit?.t ?? .infinity, "\(name) t at \(pixel)")
        XCTAssertEqual(
          buffers.normals[pixel], hit?.normal ?? .zero,
          "\(name) normal at \(pixel)")
        if hit != nil { hits += 1 }
      }
    }
    XCTAssertGreaterThan(hits, 0, "\(name) shows something")
  }

  func testCompiled_MatchesTheModel_MeshAndTransforms() throws {
    try compare("mesh-and-transforms")
  }

  func testCompiled_MatchesTheModel_CourseLikeScene() throws {
    try compare("spheres")
  }

  func testCompiled_MatchesTheModel_NestedGroups() throws {
    try compare("spheres-only")
  }

  func testFlattened_BakesSimilaritiesAndKeepsEllipsoids() throws {
    let scene = try SceneParser.parse(
      contentsOf: "\(Self.scenesFolder)/mesh-and-transforms.txt")
    let all = scene.root.flattened()
    XCTAssertEqual(all.triangles.count, 21)
    XCTAssertEqual(
      all.transformedSpheres.count, 1, "a non-uniform scale makes an ellipsoid")
    XCTAssertEqual(all.planes.count, 1)
    XCTAssertEqual(all.planes.first?.offset ?? 0, -1.6, accuracy: 1e-15)
  }
}
