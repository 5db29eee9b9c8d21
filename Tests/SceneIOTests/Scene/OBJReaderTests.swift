import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

final class OBJReaderTests: XCTestCase {
  func parse(_ text: String) throws(SceneError) -> OBJMesh {
    try OBJReader.parse(text, file: "mesh.obj")
  }

  func triangle(
    _ v: SIMD3<Int32>, _ n: SIMD3<Int32>? = nil, texture t: SIMD3<Int32>? = nil
  ) -> OBJTriangle {
    OBJTriangle(vertexIndices: v, normalIndices: n, textureIndices: t)
  }

  /// Four vertices, three texture coordinates and three normals.
  static let elements = """
    v 0 0 0
    v 1 0 0
    v 0 1 0
    v 0 0 1
    vt 0 0
    vt 1 0
    vt 0 1
    vn 0 0 1
    vn 1 0 0
    vn 0 1 0

    """

  // MARK: - Well-formed files

  /// Each face form: v, v/vt, v//vn and v/vt/vn; indices become 0-based,
  /// texture coordinates and normals kept.
  /// A UTF-8 byte-order mark at the start is skipped, and columns count
  /// from after it.
  func testParse_ByteOrderMarkSkipped() throws {
    let mesh = try parse("\u{FEFF}" + Self.elements + "f 1 2 3\n")
    XCTAssertEqual(mesh.vertices.count, 4)
    do {
      _ = try parse("\u{FEFF}vx 1 2 3\n")
      XCTFail("an unknown statement")
    } catch {
      XCTAssertTrue(
        error.description.hasPrefix("mesh.obj:1:1: "), error.description)
    }
  }

  func testParse_FaceForms() throws {
    let mesh = try parse(
      Self.elements + """
        f 1 2 3
        f 1/1 2/2 4/3
        f 1//1 3//2 4//3
        f 2/1/3 3/2/2 4/3/1
        """)
    XCTAssertEqual(
      mesh.vertices,
      [Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)])
    XCTAssertEqual(
      mesh.normals, [Vector3(0, 0, 1), Vector3(1, 0, 0), Vector3(0, 1, 0)])
    XCTAssertEqual(
      mesh.triangles,
      [
        triangle(SIMD3(0, 1, 2)),
        triangle(SIMD3(0, 1, 3), texture: SIMD3(0, 1, 2)),
        triangle(SIMD3(0, 2, 3), SIMD3(0, 1, 2)),
        triangle(SIMD3(1, 2, 3), SIMD3(2, 1, 0), texture: SIMD3(0, 1, 2)),
      ])
    XCTAssertNil(mesh.triangles[1].normalIndices)
    XCTAssertEqual(
      mesh.textureCoordinates,
      [
        TextureCoordinate(0, 0), TextureCoordinate(1, 0),
        TextureCoordinate(0, 1),
      ])
  }

  /// Negative indices count back from the latest element defined so far,
  /// and may be mixed with positive ones.
  func testParse_NegativeIndices() throws {
    let mesh = try parse(
      Self.elements + """
        f -4 -3 -2
        f -1//-1 -2//1 4//-3
        v 5 5 5
        f -1 1 -2
        f -1/-3 -2/-2 -3/-1
        """)
    XCTAssertEqual(
      mesh.triangles,
      [
        triangle(SIMD3(0, 1, 2)), triangle(SIMD3(3, 2, 3), SIMD3(2, 0, 0)),
        triangle(SIMD3(4, 0, 3)),
        triangle(SIMD3(4, 3, 2), texture: SIMD3(0, 1, 2)),
      ])
  }

  /// Polygons are fanned from their first vertex: a quad into two
  /// triangles, a pentagon into three, normals following their vertices.
  func testParse_Fans() throws {
    let mesh = try parse(
      """
      v 0 0 0
      v 1 0 0
      v 1 1 0
      v 0 1 0
      v -1 0.5 0
      vn 0 0 1
      vn 0 0 2
      vn 0 0 3
      vn 0 0 4
      f 1 2 3 4
      f 1//4 2//3 3//2 4//1 5//1
      """)
    XCTAssertEqual(
      mesh.triangles,
      [
        triangle(SIMD3(0, 1, 2)), triangle(SIMD3(0, 2, 3)),
        triangle(SIMD3(0, 1, 2), SIMD3(3, 2, 1)),
        triangle(SIMD3(0, 2, 3), SIMD3(3, 1, 0)),
        triangle(SIMD3(0, 3, 4), SIMD3(3, 0, 0)),
      ])
  }

  /// Comments (whole-line and trailing), blank lines, indentation, tabs,
  /// CRLF line ends, the ignored statements with whatever arguments, w and
  /// vertex colours, one to three texture coordinates, line continuations,
  /// and a last line without a newline.
  func testParse_CommentsAndIgnoredStatements() throws {
    let text =
      "# exported by hand\r\n"
      + "mtllib scene.mtl other.mtl\r\n"
      + "o Cube\r\n"
      + "g left right\r\n"
      + "\r\n"
      + "   v 1 2 3 # a trailing comment\r\n"
      + "\tv\t4 5 6 1.0\r\n"
      + "v 7 8 9 0.5 0.25 1\r\n"
      + "vt 0.5\n" + "vt 0.5 0.25\n" + "vt 0.5 0.25 0\n"
      + "vn 0 0 1\n"
      + "usemtl red\n" + "s off\n" + "s 1\n" + "mg 1 2\n" + "lod 3\n"
      + "usemap wood\n" + "maplib wood.tex\n" + "shadow_obj shadow.obj\n"
      + "#\n"
      + "f 1/3/1 \\\n"
      + "  2/2/1 \\   \n"
      + "  3/1/1"
    let mesh = try parse(text)
    XCTAssertEqual(
      mesh.vertices, [Vector3(1, 2, 3), Vector3(4, 5, 6), Vector3(7, 8, 9)])
    XCTAssertEqual(mesh.normals, [Vector3(0, 0, 1)])
    XCTAssertEqual(
      mesh.triangles,
      [triangle(SIMD3(0, 1, 2), SIMD3(0, 0, 0), texture: SIMD3(2, 1, 0))])
    XCTAssertEqual(
      mesh.textureCoordinates,
      [
        TextureCoordinate(0.5, 0), TextureCoordinate(0.5, 0.25),
        TextureCoordinate(0.5, 0.25),
      ], "a missing v is 0; w is dropped")
  }

  /// Line numbers count physical lines, continuations included.
  func testParse_LineNumbersAfterContinuation() {
    XCTAssertThrowsError(try parse("v 0 0 0\nf 1 \\\n 1 \\\n 2\n")) { error in
      let error = error as? SceneError
      XCTAssertEqual(error?.line, 4)
      XCTAssertEqual(error?.column, 2)
    }
  }

  /// Empty input, blank lines and comments alone give an empty mesh.
  func testParse_Empty() throws {
    for text in ["", "\n\n", "# nothing\n   \n\t# here", "\r\n"] {
      XCTAssertEqual(try parse(text), OBJMesh(), text.debugDescription)
    }
  }

  /// Numbers in every form DecimalParser reads, rounded correctly.
  func testParse_NumberForms() throws {
    let mesh = try parse("v -1.5e2 +0.1 .25\nv 1E-3 -0 12345678901234567890\n")
    XCTAssertEqual(mesh.vertices[0], Vector3(-150, 0.1, 0.25))
    // 20 digits take the slow path, which rounds to the nearest Double.
    XCTAssertEqual(
      mesh.vertices[1], Vector3(0.001, 0, 12_345_678_901_234_567_168))
  }

  /// The mesh as model triangles, in either precision, with its normals.
  func testMakeTriangles() throws {
    let mesh = try parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.1 0 0\nvn 0 0 1\nf 1 2 3\nf 1//1 4//1 "
        + "3//1\n"
    )
    let triangles = mesh.makeTriangles(materialIndex: 2, as: Float.self)
    XCTAssertEqual(triangles.count, 2)
    XCTAssertEqual(
      triangles[0],
      Triangle(
        Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), materialIndex: 2))
    XCTAssertEqual(triangles[1].v1, Vector3(Float(0.1), 0, 0))
    XCTAssertEqual(triangles[1].vertexNormals?.n2, Vector3(0, 0, 1))
    XCTAssertNil(triangles[0].vertexNormals)
  }

  /// Reading a file, and a missing file reported at line 0.
  func testRead_ContentsOfFile() throws {
    let path = FileManager.default.temporaryDirectory
      .appendingPathComponent("raytrace-mesh-\(UUID().uuidString).obj").path
    try Data("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".utf8).write(
      to: URL(fileURLWithPath: path))
    defer { try? FileManager.default.removeItem(atPath: path) }
    XCTAssertEqual(try OBJReader.read(contentsOf: path).triangles.count, 1)

    let missing = path + ".missing"
    XCTAssertThrowsError(try OBJReader.read(contentsOf: missing)) { error in
      XCTAssertEqual(
        (error as? SceneError)?.description,
        "\(missing): error: cannot open the file: No such file or directory")
    }
  }

  /// A 100×100 grid of quads (20,000 triangles), as exporters write them,
  /// fans into the expected triangles. (Speed is measured in a release
  /// build, outside the tests: a debug build says little about it.)
  func testParse_GridMesh() throws {
    let n = 100
    var text = ""
    for j in 0...n {
      for i in 0...n {
        text += "v \(Double(i) / 8) \(Double(j) / 8) 0.125\n"
      }
    }
    for j in 0..<n {
      for i in 0..<n {
        let a = j * (n + 1) + i + 1
        text += "f \(a) \(a + 1) \(a + n + 2) \(a + n + 1)\n"
      }
    }
    let mesh = try parse(text)
    XCTAssertEqual(mesh.vertices.count, (n + 1) * (n + 1))
    XCTAssertEqual(mesh.triangles.count, 2 * n * n)
    // The last quad, 10099 10100 10201 10200 (1-based), fans into
    // (10099, 10201, 10200).
    XCTAssertEqual(mesh.triangles.last, triangle(SIMD3(10_098, 10_200, 10_199)))
  }
}
