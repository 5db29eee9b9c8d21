import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Triangles compiled straight from the meshes' indexed storage
/// (`CompiledScene.compileTriangles`): each record, material and normal the
/// one its model triangle gives, in scene order.
final class CompiledSceneMeshesTests: XCTestCase {
  func scene() throws -> Scene {
    let given = TriangleMesh(
      try OBJReader.parse(Fixtures.mixedOBJ, file: "mixed.obj"),
      materialIndex: 1, normals: .unitMean)
    let smoothed = TriangleMesh(
      try OBJReader.parse(Fixtures.plainOBJ, file: "plain.obj"),
      materialIndex: 2, normals: .unitMean)
    let loose = Triangle<Double>(
      Vector3(-0.5, 0, 0.2), Vector3(0.3, 0.1, 0.6), Vector3(0, 0.8, 0.3),
      vertexNormals: .init(
        Vector3(0, 0, 1), Vector3(0, 1, 1), Vector3(1, 0, 1)),
      materialIndex: 0)
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0.3, 0.4, 60), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 5))
    return Scene(
      camera: camera, materials: Array(repeating: .defaultWhite, count: 3),
      root: Group([
        .mesh(smoothed), .triangle(loose), .mesh(given), .triangle(loose),
      ]))
  }

  func check<Kernel: IntersectionKernel>(_: Kernel.Type) throws {
    let scene = try scene()
    // Projected, so kept in scene order; none is large (`TrianglePlane`)
    // from 60 units away, none degenerate.
    let compiled = CompiledScene<Kernel>(scene, triangleProjectionThreshold: 0)
    let model = Array(scene.root.flattened().triangles)
    XCTAssertEqual(compiled.triangleCount, model.count)
    XCTAssertEqual(compiled.ordinaryTriangleCount, model.count)
    let eye = scene.camera.center
    let relative = Kernel.frameOrigin(eye: eye) == .zero
    for (index, triangle) in model.enumerated() {
      let record = compiled.triangles[index]
      func frame(_ p: Vector3<Double>) -> Vector3<Kernel.Scalar> {
        CompiledScene<Kernel>.frame(p, eye: eye, cameraRelative: relative)
      }
      XCTAssertEqual(record.v0, frame(triangle.v0), "\(index)")
      XCTAssertEqual(record.v1, frame(triangle.v1), "\(index)")
      XCTAssertEqual(record.v2, frame(triangle.v2), "\(index)")
      XCTAssertEqual(
        compiled.materialIndex(of: .triangle(index)), triangle.materialIndex)
      let normals = compiled.vertexNormals(ofTriangle: index)
      XCTAssertEqual(normals?.n0, triangle.vertexNormals.map { .init($0.n0) })
      XCTAssertEqual(normals?.n1, triangle.vertexNormals.map { .init($0.n1) })
      XCTAssertEqual(normals?.n2, triangle.vertexNormals.map { .init($0.n2) })
    }
  }

  func testRecords_AsTheModelTriangles() throws {
    try check(StableKernel<Double>.self)
    try check(StableKernel<Float>.self)
    try check(NaiveKernel<Double>.self)
    try check(NaiveKernel<Float>.self)
  }

  /// Each compiled triangle's material and normals are its face's
  /// (`TriangleSources`) with a degenerate face left out and the rest in
  /// the hierarchy's order; in scene order, with every face kept, no face
  /// numbers are stored.
  func testSources_FacesThroughDegenerateAndHierarchy() throws {
    var scene = try scene()
    let degenerate = Triangle<Double>(
      Vector3(0, 0, 0), Vector3(1, 1, 1), Vector3(2, 2, 2), materialIndex: 2)
    scene.root = Group([.triangle(degenerate)] + scene.root.objects)
    let model = Array(scene.root.flattened().triangles)
    let compiled = CompiledScene<StableKernel<Double>>(
      scene, hierarchyThreshold: 2)
    let hierarchy = try XCTUnwrap(compiled.triangleHierarchy)
    XCTAssertEqual(compiled.triangleCount, model.count - 1)
    XCTAssertFalse(compiled.triangleSources.followsFaces)
    for index in 0..<compiled.triangleCount {
      let triangle = model[Int(hierarchy.order[index]) + 1]
      XCTAssertEqual(
        compiled.materialIndex(of: .triangle(index)), triangle.materialIndex,
        "\(index)")
      let normals = compiled.vertexNormals(ofTriangle: index)
      XCTAssertEqual(normals?.n0, triangle.vertexNormals?.n0, "\(index)")
      XCTAssertEqual(normals?.n1, triangle.vertexNormals?.n1, "\(index)")
      XCTAssertEqual(normals?.n2, triangle.vertexNormals?.n2, "\(index)")
    }
    let projected = CompiledScene<StableKernel<Double>>(
      try self.scene(), triangleProjectionThreshold: 0)
    XCTAssertTrue(projected.triangleSources.followsFaces)
  }

  /// A Double render shares the normals of a scene's only mesh with
  /// normals with the model; a Float render converts them.
  func testNormals_SharedInDouble() throws {
    var scene = try scene()
    guard case .mesh(let smoothed) = scene.root.objects[0] else {
      return XCTFail("the scene starts with a mesh")
    }
    let flat = Triangle<Double>(
      Vector3(-0.5, 0, 0.2), Vector3(0.3, 0.1, 0.6), Vector3(0, 0.8, 0.3))
    scene.root = Group([.triangle(flat), .mesh(smoothed)])
    func address<T>(_ array: [T]) -> UnsafeRawPointer? {
      array.withUnsafeBufferPointer { UnsafeRawPointer($0.baseAddress) }
    }
    let double = CompiledScene<StableKernel<Double>>(scene)
    XCTAssertEqual(address(double.vertexNormals), address(smoothed.normals))
    let float = CompiledScene<StableKernel<Float>>(scene)
    XCTAssertEqual(float.vertexNormals, smoothed.normals.map { .init($0) })
  }

  /// A mesh compiled in parts on several threads is the mesh compiled on
  /// one: the same records, texture coordinates, materials, normals, exact
  /// planes and large triangles, in the same order, with degenerate, thin
  /// and large faces in every part.
  func testParts_AsOneThread() throws {
    var random = SplitMix64(seed: 38)
    func next() -> Double { Double(random.next() >> 11) * 0x1p-53 }
    var mesh = TriangleMesh<Double>()
    for index in 0..<30_000 {
      let a = Vector3(4 * next() - 2, 4 * next() - 2, 2 * next() - 1)
      var (b, c) = (
        a + Vector3(0.1 * next(), 0.1 * next(), 0),
        a + Vector3(0, 0.1 * next(), 0.1 * next())
      )
      if index % 97 == 3 {
        (b, c) = (a, a + Vector3(1, 1, 1))  // degenerate
      } else if index % 211 == 7 {
        (b, c) = (a + Vector3(1, 0, 0), a + Vector3(0.5, 1e-7, 0))  // thin
      }
      var triangle = Triangle(a, b, c, materialIndex: index % 3)
      if index % 1009 == 11 {  // large beside its distance from the eye
        triangle = Triangle(
          Vector3(-1e6, -0.5, 4), Vector3(1e6, -0.5, 4),
          Vector3(0, -0.5, -1e6), materialIndex: 1)
      }
      if index % 2 == 0 {
        triangle.vertexNormals = .init(
          Vector3(0, 0, 1), Vector3(0, next(), 1), Vector3(next(), 0, 1))
      }
      if index % 3 != 1 {
        triangle.textureCoordinates = .init(
          TextureCoordinate(next(), next()), TextureCoordinate(0, 1),
          TextureCoordinate(1, next()))
      }
      mesh.append(triangle)
    }
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0, 0, 5), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 30))
    let scene = Scene(
      camera: camera, materials: Array(repeating: .defaultWhite, count: 3),
      root: Group([.mesh(mesh)]))
    let texture = Texture(
      image: Image8(width: 1, height: 1, bytes: [255, 128, 0]))
    func compiled(_ threads: Int, textured: Bool = true)
      -> CompiledScene<StableKernel<Double>>
    {
      CompiledScene(
        scene, textures: textured ? [texture, nil, nil] : [],
        triangleProjectionThreshold: 0, threads: threads)
    }
    // Untextured, no part writes texture coordinates.
    let untextured = (
      compiled(1, textured: false), compiled(4, textured: false)
    )
    XCTAssertEqual(untextured.0.triangleCount, untextured.1.triangleCount)
    XCTAssertTrue(untextured.1.triangleTextureCoordinates.isEmpty)
    let one = compiled(1)
    XCTAssertLessThan(one.ordinaryTriangleCount, one.triangleCount)
    XCTAssertLessThan(one.triangleCount, mesh.count)
    XCTAssertFalse(one.exactPlanes.isEmpty)
    XCTAssertFalse(one.triangleSources.followsFaces)
    // Exactly the ordinary triangles that need an exact plane have one.
    XCTAssertEqual(one.exactPlaneIndices.count, one.triangleCount)
    for index in 0..<one.ordinaryTriangleCount {
      let record = one.triangles[index]
      XCTAssertEqual(
        one.exactPlaneIndices[index] >= 0,
        TrianglePlane.needsExactT(relative: (record.v0, record.v1, record.v2)),
        "\(index)")
    }
    // 30,000 faces: two parts on 2 threads, three on 3 or more.
    for threads in Self.quickCases([2, 3, 5], half: 1) {
      let parts = compiled(threads)
      XCTAssertEqual(parts.triangleCount, one.triangleCount)
      XCTAssertEqual(parts.ordinaryTriangleCount, one.ordinaryTriangleCount)
      XCTAssertEqual(parts.exactPlaneIndices, one.exactPlaneIndices)
      XCTAssertEqual(parts.exactPlanes.count, one.exactPlanes.count)
      for (p, q) in zip(parts.exactPlanes, one.exactPlanes) {
        XCTAssertEqual(p.normal, q.normal)
        XCTAssertEqual(p.distance, q.distance)
      }
      XCTAssertEqual(parts.trianglePlanes.count, one.trianglePlanes.count)
      for (p, q) in zip(parts.trianglePlanes, one.trianglePlanes) {
        XCTAssertEqual(p.plane.normal, q.plane.normal)
        XCTAssertEqual(p.plane.distance, q.plane.distance)
      }
      XCTAssertEqual(
        parts.triangleTextureCoordinates, one.triangleTextureCoordinates)
      for index in 0..<one.triangleCount {
        let (p, q) = (parts.triangles[index], one.triangles[index])
        guard p.v0 == q.v0, p.v1 == q.v1, p.v2 == q.v2,
          parts.materialIndex(of: .triangle(index))
            == one.materialIndex(of: .triangle(index)),
          parts.vertexNormals(ofTriangle: index)
            == one.vertexNormals(ofTriangle: index)
        else {
          return XCTFail("triangle \(index) differs on \(threads) threads")
        }
      }
    }
  }
}
