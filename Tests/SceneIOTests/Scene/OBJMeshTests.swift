import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// The two smoothing rules, the course's reading of `a/b` faces and the
/// mesh's texture coordinates.
final class OBJMeshTests: XCTestCase {
  /// Two faces of very unequal area meeting at a right angle along the
  /// edge from vertex 0 to vertex 1: a large one in the plane z = 0
  /// (normal +z, area 50) and a small one in the plane x = 0 (normal +x,
  /// area 0.5).
  static let hinge = """
    v 0 0 0
    v 0 1 0
    v 10 0 0
    v 0 0 1
    f 1 3 2
    f 1 2 4
    """

  /// Area weighting sums the unnormalised cross products: at the shared
  /// vertices (10, 0, 0) + ... gives (1, 0, 10)/|·| in direction, where
  /// the unit mean gives (1, 0, 1)/√2. Checked within 4 ε per component
  /// (a normalisation of exact sums: one rounding each for the sum, the
  /// squares, the root and the division).
  func testSmoothed_AreaWeightedAgainstUnitMean() throws {
    let mesh = try OBJReader.parse(Self.hinge, file: "hinge.obj")
    let area = mesh.smoothed(.areaWeighted)
    let mean = mesh.smoothed(.unitMean)
    // Face 1 (1 3 2): (10,0,0) × (0,1,0) = (0, 0, 10); face 2 (1 2 4):
    // (0,1,0) × (0,0,1) = (1, 0, 0).
    let weighted = Vector3<Double>(1, 0, 10).normalized()
    let unit = Vector3<Double>(1, 0, 1).normalized()
    for vertex in [0, 1] {
      assertClose(area.normals[vertex], weighted, "area, vertex \(vertex)")
      assertClose(mean.normals[vertex], unit, "mean, vertex \(vertex)")
    }
    // A vertex of one face only has that face's normal under both rules.
    assertClose(area.normals[2], Vector3(0, 0, 1), "area, vertex 2")
    assertClose(mean.normals[3], Vector3(1, 0, 0), "mean, vertex 3")
    XCTAssertEqual(area.triangles[0].normalIndices, SIMD3(0, 2, 1))
  }

  /// The style picks the rule: the course's loader weighs by area, the
  /// MIT images by the unit mean.
  func testOptions_StylePicksTheRule() {
    XCTAssertEqual(SceneOptions(style: .course).meshNormals, .areaWeighted)
    XCTAssertEqual(SceneOptions(style: .mit).meshNormals, .unitMean)
  }

  /// A file with `vn` lines keeps them, whatever the rule.
  func testSmoothed_KeepsGivenNormals() throws {
    let mesh = try OBJReader.parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 3\nf 1//1 2//1 3//1\n",
      file: "given.obj")
    XCTAssertEqual(mesh.smoothed(.areaWeighted), mesh)
  }

  /// `a/b` with only `vn` lines defined reads b as a normal (the course's
  /// files); with `vt` lines, as a texture coordinate, which a material
  /// without a texture reads back as a normal when the file has both.
  func testCourseFaceReading() throws {
    let normalsOnly = try OBJReader.parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 1\nf 1/2 2/1 3/2\n",
      file: "a.obj")
    XCTAssertEqual(normalsOnly.triangles[0].normalIndices, SIMD3(1, 0, 1))
    XCTAssertNil(normalsOnly.triangles[0].textureIndices)

    let both = try OBJReader.parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\nvn 0 1 1\n"
        + "f 1/2 2/1 3/2\n",
      file: "b.obj")
    XCTAssertEqual(both.triangles[0].textureIndices, SIMD3(1, 0, 1))
    let untextured = try XCTUnwrap(both.readingTextureIndicesAsNormals())
    XCTAssertEqual(untextured.triangles[0].normalIndices, SIMD3(1, 0, 1))
    XCTAssertNil(untextured.triangles[0].textureIndices)

    let tooFewNormals = try OBJReader.parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvt 1 0\nvn 0 0 1\n"
        + "f 1/3 2/1 3/2\n",
      file: "c.obj")
    XCTAssertNil(tooFewNormals.readingTextureIndicesAsNormals())
  }

  /// Triangles carry their vertices' (u, v), interpolated at a point with
  /// the barycentric weights: (0.25, 0.5), where the ray from (0.25, 0.5, 1)
  /// down −z hits (the fast engine's tests hit textured triangles).
  func testMakeTriangles_TextureCoordinates() throws {
    let mesh = try OBJReader.parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
      file: "uv.obj")
    let triangle = try XCTUnwrap(
      mesh.makeTriangles(materialIndex: 0, as: Double.self).first)
    let coordinates = try XCTUnwrap(triangle.textureCoordinates)
    // Weights of v0, v1, v2 at (0.25, 0.5): 1 − 0.25 − 0.5, 0.25, 0.5.
    let uv = coordinates.at(u: 0.25, v: 0.25, w: 0.5)
    XCTAssertEqual(uv.u, 0.25, accuracy: 4 * Double.ulpOfOne)
    XCTAssertEqual(uv.v, 0.5, accuracy: 4 * Double.ulpOfOne)
  }

  private func assertClose(
    _ got: Vector3<Double>, _ want: Vector3<Double>, _ label: String,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    let error = (got - want).maxMagnitude
    XCTAssertLessThanOrEqual(
      error, 4 * Double.ulpOfOne, "\(label): \(got) against \(want)",
      file: file, line: line)
  }

  /// Faces kept as index arrays come back as the faces that went in, with
  /// and without normals and texture coordinates in any order; the index
  /// arrays of faces without stay empty until a face gives some.
  func testTriangles_IndexArraysRoundTrip() {
    let faces = [
      OBJTriangle(vertexIndices: SIMD3(0, 1, 2)),
      OBJTriangle(
        vertexIndices: SIMD3(2, 1, 3), normalIndices: SIMD3(0, 0, 1)),
      OBJTriangle(
        vertexIndices: SIMD3(3, 1, 0), textureIndices: SIMD3(1, 2, 0)),
      OBJTriangle(
        vertexIndices: SIMD3(0, 2, 3), normalIndices: SIMD3(1, 1, 0),
        textureIndices: SIMD3(2, 2, 1)),
    ]
    for count in 0...faces.count {
      let mesh = OBJMesh(triangles: Array(faces.prefix(count)))
      XCTAssertEqual(mesh.triangles, Array(faces.prefix(count)))
      XCTAssertEqual(mesh.triangleCount, count)
      XCTAssertEqual(mesh.normalIndices.isEmpty, count < 2)
      XCTAssertEqual(mesh.textureIndices.isEmpty, count < 3)
      XCTAssertEqual(mesh.hasTextureCoordinates, count >= 3)
    }
  }

  /// The scene's mesh shares the file's vertex indices: no copy.
  func testTriangleMesh_SharesTheIndices() throws {
    let obj = try OBJReader.parse(Self.hinge, file: "hinge.obj")
    let mesh = TriangleMesh(obj, materialIndex: 0, normals: .unitMean)
    XCTAssertEqual(
      mesh.vertexIndices.withUnsafeBufferPointer { $0.baseAddress },
      obj.vertexIndices.withUnsafeBufferPointer { $0.baseAddress })
  }

  /// Normals summed by several threads, each owning a range of vertices,
  /// are those of one thread bit for bit (each vertex's sum in the faces'
  /// order), with faces that span the ranges, repeat a corner, or are
  /// degenerate.
  func testSmoothedNormals_SameOnAnyThreads() {
    var random = SplitMix64(seed: 5)
    func next() -> Double { Double(random.next() >> 11) * 0x1p-53 }
    let count = 70_000
    let vertices = (0..<count).map { _ in Vector3(next(), next(), next()) }
    let triangles = (0..<2 * count).map { face -> OBJTriangle in
      func corner() -> Int32 { Int32(random.next() % UInt64(count)) }
      let a = corner()
      return OBJTriangle(
        vertexIndices: SIMD3(a, face % 11 == 0 ? a : corner(), corner()))
    }
    let mesh = OBJMesh(vertices: vertices, triangles: triangles)
    for rule in [MeshNormals.unitMean, .areaWeighted] {
      let one = mesh.smoothedNormals(rule, threads: 1)
      XCTAssertNotNil(one)
      for threads in [2, 3, 4] {
        let parts = mesh.smoothedNormals(rule, threads: threads)
        XCTAssertTrue(one == parts, "\(rule) on \(threads) threads")
      }
    }
  }
}
