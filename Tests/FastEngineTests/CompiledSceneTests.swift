import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The compiled scene (flattened, transforms baked into world space or
/// carried as ellipsoids, camera-relative, hierarchies, per-tile culling)
/// against the public model's own `Intersectable` path (groups and
/// transforms intersected as the scene file nests them), pixel by pixel.
final class CompiledSceneTests: XCTestCase {
  static var scenesFolder: String {
    return ProjectFiles.projectFolder + "/scenes"
  }

  /// The compiled scene's depth and normals are the model's, bit for bit:
  /// the same functions on the same numbers (see `CourseEngine`), here
  /// with the hierarchy thresholds of `CompiledScene`'s defaults rather
  /// than the command line's.
  func compare(_ name: String, width: Int = 48, height: Int = 36) throws {
    try compare(
      SceneParser.parse(contentsOf: "\(Self.scenesFolder)/\(name).txt"),
      name, width: width, height: height)
  }

  func compare(
    _ scene: Scene, _ name: String, width: Int = 48, height: Int = 36
  ) throws {
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals], threads: 2)
    let buffers = Renderer.render(
      CompiledScene<StableKernel<Double>>(scene), settings: settings)
    let camera = scene.camera
    let aspect = Double(height) / Double(width)
    var hits = 0
    for row in 0..<height {
      for column in 0..<width {
        let x: Double = settings.screen.x(column: column)
        let y: Double = settings.screen.y(row: row)
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

  /// Meshes with and without vertex normals and texture coordinates,
  /// placed by transforms and not, beside loose triangles and a twin of
  /// one mesh (ties), compiled from the meshes' indexed storage.
  func testCompiled_MatchesTheModel_MeshesAndLooseTriangles() throws {
    let obj = try OBJReader.parse(
      Fixtures.mixedOBJ, file: "mixed.obj")
    let given = TriangleMesh(obj, materialIndex: 1, normals: .unitMean)
    let smoothed = TriangleMesh(
      try OBJReader.parse(Fixtures.plainOBJ, file: "plain.obj"),
      materialIndex: 0, normals: .areaWeighted)
    let loose = Triangle<Double>(
      Vector3(-0.5, 0, 0.2), Vector3(0.3, 0.1, 0.6), Vector3(0, 0.8, 0.3),
      vertexNormals: .init(
        Vector3(0, 0, 1), Vector3(0, 1, 1), Vector3(1, 0, 1)),
      materialIndex: 2)
    let matrix =
      Matrix4<Double>.translation(Vector3(-1.5, 0.25, -0.5))
      * Matrix4.rotationY(degrees: 40) * Matrix4.scale(Vector3(1, 0.5, 2))
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0.3, 0.4, 6), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 40))
    let root = Group([
      .triangle(loose), .mesh(given),
      .transform(
        try XCTUnwrap(Transform(matrix: matrix, object: .mesh(given)))),
      .mesh(smoothed), .triangle(loose),
      .group(Group([.mesh(given), .triangle(loose)])),
      .transform(
        try XCTUnwrap(
          Transform(
            matrix: Matrix4.translation(Vector3(1.2, -1, 0)),
            object: .mesh(smoothed)))),
    ])
    try compare(
      Scene(
        camera: camera, materials: Array(repeating: .defaultWhite, count: 3),
        root: root), "meshes")
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
