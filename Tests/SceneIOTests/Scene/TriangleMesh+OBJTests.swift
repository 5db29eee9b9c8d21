import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// A mesh file's triangles as the scene keeps them, indexed
/// (`TriangleMesh(_:materialIndex:normals:)`): the same triangles, bit for
/// bit and in order, as the array the loader made of them before.
final class TriangleMeshOBJTests: XCTestCase {
  static let plain = Fixtures.plainOBJ
  static let mixed = Fixtures.mixedOBJ

  func assertSameTriangles(
    _ text: String, rule: MeshNormals, file: StaticString = #filePath,
    line: UInt = #line
  ) throws {
    let obj = try OBJReader.parse(text, file: "mesh.obj")
    let want = obj.smoothed(rule).makeTriangles(
      materialIndex: 3, as: Double.self)
    let mesh = TriangleMesh(obj, materialIndex: 3, normals: rule)
    XCTAssertEqual(mesh.count, want.count, file: file, line: line)
    XCTAssertEqual(Array(mesh), want, file: file, line: line)
    // Random access gives the same as iteration.
    for index in want.indices.reversed() {
      XCTAssertEqual(mesh[index], want[index], file: file, line: line)
    }
  }

  func testTriangles_SmoothedAsTheArray() throws {
    for rule in [MeshNormals.unitMean, .areaWeighted] {
      try assertSameTriangles(Self.plain, rule: rule)
    }
    let mesh = TriangleMesh(
      try OBJReader.parse(Self.plain, file: "plain.obj"), materialIndex: 0,
      normals: .unitMean)
    // A normal per vertex, indexed by the vertex indices: no normal
    // indices of its own.
    XCTAssertTrue(mesh.normalsFollowVertices)
    XCTAssertTrue(mesh.normalIndices.isEmpty)
    XCTAssertTrue(mesh.textureIndices.isEmpty)
    XCTAssertEqual(mesh.normals.count, mesh.vertices.count)
    XCTAssertTrue(mesh.allSatisfy { $0.vertexNormals != nil })
  }

  func testTriangles_GivenNormalsAndCoordinatesAsTheArray() throws {
    try assertSameTriangles(Self.mixed, rule: .unitMean)
    let mesh = TriangleMesh(
      try OBJReader.parse(Self.mixed, file: "mixed.obj"), materialIndex: 0,
      normals: .unitMean)
    XCTAssertFalse(mesh.normalsFollowVertices)
    XCTAssertEqual(
      mesh.map { $0.vertexNormals != nil },
      [true, false, true, false, true, true])
    XCTAssertEqual(
      mesh.map { $0.textureCoordinates != nil },
      [true, false, false, true, true, true])
  }

  /// The course's `a/b` read as normals for an untextured material.
  func testTriangles_TextureIndicesReadAsNormals() throws {
    let obj = try XCTUnwrap(
      try OBJReader.parse(Self.mixed, file: "mixed.obj")
        .readingTextureIndicesAsNormals())
    let mesh = TriangleMesh(obj, materialIndex: 1, normals: .unitMean)
    XCTAssertEqual(
      Array(mesh), obj.makeTriangles(materialIndex: 1, as: Double.self))
  }

  func testTriangles_EmptyFile() throws {
    let mesh = TriangleMesh(
      try OBJReader.parse("", file: "empty.obj"), materialIndex: 0,
      normals: .unitMean)
    XCTAssertTrue(mesh.isEmpty)
  }
}
