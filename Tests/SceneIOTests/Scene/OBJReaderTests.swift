import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import Numerics
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
      XCTAssertTrue(error.description.hasPrefix("mesh.obj:1:1: "), error.description)
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
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.1 0 0\nvn 0 0 1\nf 1 2 3\nf 1//1 4//1 3//1\n"
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

  // MARK: - Malformed files

  struct Malformed {
    var name: String
    var text: String
    var line: Int
    var column: Int
    var message: String
  }

  /// Three vertices on lines 1 to 3: what follows starts on line 4.
  static let triangleVertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

  static let malformed: [Malformed] = {
    let h = triangleVertices
    let validVertices =
      "3 vertices are defined before this face (valid: 1 to 3 or -3 to -1)"
    return [
      // Keywords.
      Malformed(
        name: "misspelt keyword", text: "vx 1 2 3", line: 1, column: 1,
        message: "expected a statement keyword, found 'vx'; did you mean 'v'?"),
      Malformed(
        name: "upper-case keyword", text: h + "  F 1 2 3", line: 4, column: 3,
        message: "expected a statement keyword, found 'F'; did you mean 'f'?"),
      Malformed(
        name: "unknown keyword", text: "frobnicate 1", line: 1, column: 1,
        message:
          "expected a statement keyword (v, vn, vt, f, o, g, s, usemtl, mtllib), "
          + "found 'frobnicate'"),
      Malformed(
        name: "number for a keyword", text: "v 0 0 0\n1.5 2 3", line: 2,
        column: 1,
        message: "expected a statement keyword, found the number 1.5"),
      Malformed(
        name: "line element", text: h + "l 1 2", line: 4, column: 1,
        message:
          "'l' (a line element) is not supported: only faces ('f') are read"),
      Malformed(
        name: "point element", text: h + "p 1", line: 4, column: 1,
        message:
          "'p' (a point element) is not supported: only faces ('f') are read"),
      Malformed(
        name: "free-form curve", text: "cstype bspline", line: 1, column: 1,
        message:
          "'cstype' (free-form geometry) is not supported: only polygonal faces "
          + "('f') are read"),
      Malformed(
        name: "control character", text: "v\u{1B}x 1", line: 1, column: 1,
        message:
          "expected a statement keyword (v, vn, vt, f, o, g, s, usemtl, mtllib), "
          + "found 'v\\u{1B}x'"),

      // Coordinates.
      Malformed(
        name: "missing x", text: "v", line: 1, column: 2,
        message: "expected the x coordinate of 'v', found end of line"),
      Malformed(
        name: "missing z before a comment", text: "v 1 2   # z?", line: 1,
        column: 6,
        message: "expected the z coordinate of 'v', found end of line"),
      Malformed(
        name: "missing z before CRLF", text: "v 1 2\r\nv 0 0 0", line: 1,
        column: 6,
        message: "expected the z coordinate of 'v', found end of line"),
      Malformed(
        name: "not a number", text: "v 1 abc 3", line: 1, column: 5,
        message: "expected a number for the y coordinate of 'v', found 'abc'"),
      Malformed(
        name: "comma decimal", text: "v 1 2,5 3", line: 1, column: 5,
        message: "expected a number for the y coordinate of 'v', found '2,5'"),
      Malformed(
        name: "too large", text: "v 1 2 1e999", line: 1, column: 7,
        message:
          "the z coordinate of 'v': '1e999' is beyond the finite range of "
          + "double (±1.7976931348623157e+308)"),
      Malformed(
        name: "NaN", text: "v nan 0 0", line: 1, column: 3,
        message:
          "expected a finite number for the x coordinate of 'v', found 'nan'"),
      Malformed(
        name: "bad w", text: "v 1 2 3 x", line: 1, column: 9,
        message: "expected a number for w of 'v', found 'x'"),
      Malformed(
        name: "five numbers", text: "v 1 2 3 4 5", line: 1, column: 12,
        message: "expected b of 'v x y z r g b', found end of line"),
      Malformed(
        name: "seven numbers", text: "v 1 2 3 4 5 6 7", line: 1, column: 15,
        message: "unexpected '7' after 'v x y z r g b'"),
      Malformed(
        name: "short normal", text: "vn 1 2", line: 1, column: 7,
        message: "expected the z coordinate of 'vn', found end of line"),
      Malformed(
        name: "long normal", text: "vn 1 2 3 4", line: 1, column: 10,
        message: "unexpected '4' after 'vn x y z'"),
      Malformed(
        name: "zero normal", text: "v 0 0 0\nvn 0.0 -0 0e5", line: 2,
        column: 1,
        message:
          "a normal of zero length has no direction: 'vn' needs a "
          + "component other than zero"),
      Malformed(
        name: "empty texture coordinate", text: "vt", line: 1, column: 3,
        message: "expected the u coordinate of 'vt', found end of line"),
      Malformed(
        name: "long texture coordinate", text: "vt 0 0 0 0", line: 1,
        column: 10,
        message: "unexpected '0' after 'vt u v w'"),
      Malformed(
        name: "long token, quoted short",
        text: "v 1 2 " + String(repeating: "a", count: 100), line: 1, column: 7,
        message:
          "expected a number for the z coordinate of 'v', found '"
          + String(repeating: "a", count: 48) + "…'"),

      // Indices.
      Malformed(
        name: "index 0", text: h + "f 0 1 2", line: 4, column: 3,
        message:
          "vertex index 0 is invalid: OBJ indices start at 1; \(validVertices)"),
      Malformed(
        name: "index past the end", text: h + "f 1 2 4", line: 4, column: 7,
        message: "vertex index 4 is out of range: \(validVertices)"),
      Malformed(
        name: "negative index past the start", text: h + "f 1 2 -4", line: 4,
        column: 7,
        message: "vertex index -4 is out of range: \(validVertices)"),
      Malformed(
        name: "forward reference", text: "f 1 2 3\n" + h, line: 1, column: 3,
        message:
          "vertex index 1 is out of range: no vertices are defined before this face"
      ),
      Malformed(
        name: "huge index", text: h + "f 1 2 99999999999999999999", line: 4,
        column: 7,
        message:
          "vertex index 99999999999999999999 is out of range: \(validVertices)"),
      Malformed(
        name: "fractional index", text: h + "f 1.5 2 3", line: 4, column: 3,
        message: "expected an integer vertex index, found '1.5'"),
      Malformed(
        name: "bare sign", text: h + "f 1 2 -", line: 4, column: 7,
        message: "expected an integer vertex index, found '-'"),
      Malformed(
        name: "texture index not a number", text: h + "vt 0 0\nf 1/x 2/1 3/1",
        line: 5, column: 5,
        message: "expected an integer texture coordinate index, found 'x'"),
      Malformed(
        name: "texture index out of range", text: h + "vt 0 0\nf 1/1 2/2 3/1",
        line: 5, column: 9,
        message:
          "texture coordinate index 2 is out of range: 1 texture coordinate is "
          + "defined before this face (valid: 1 or -1)"),
      Malformed(
        name: "normal index without normals", text: h + "f 1//1 2//1 3//1",
        line: 4, column: 6,
        message:
          "normal index 1 is out of range: no normals are defined before this face"
      ),
      Malformed(
        name: "texture index without texture coordinates",
        text: h + "vn 0 0 1\nvn 0 1 0\nf 1/1/1", line: 6, column: 5,
        message:
          "texture coordinate index 1 is out of range: no texture coordinates are "
          + "defined before this face"),
      Malformed(
        name: "normal index 0 after a valid texture index",
        text: h + "vt 0 0\nvn 0 0 1\nvn 0 1 0\nf 1/1/0", line: 7, column: 7,
        message:
          "normal index 0 is invalid: OBJ indices start at 1; 2 normals are "
          + "defined before this face (valid: 1 to 2 or -2 to -1)"),

      // Faces.
      Malformed(
        name: "two vertices", text: h + "f 1 2", line: 4, column: 1,
        message: "a face needs at least 3 vertices, found 2"),
      Malformed(
        name: "no vertices", text: h + "f # empty", line: 4, column: 1,
        message: "a face needs at least 3 vertices, found 0"),
      Malformed(
        name: "mixed forms", text: h + "vn 0 0 1\nf 1//1 2 3//1", line: 5,
        column: 8,
        message:
          "face vertex '2' has the form v, but the face's first vertex '1//1' has "
          + "the form v//vn; all vertices of a face must use the same form"),
      Malformed(
        name: "mixed texture forms", text: h + "vt 0 0\nf 1/1 2/1 3", line: 5,
        column: 11,
        message:
          "face vertex '3' has the form v, but the face's first vertex '1/1' has "
          + "the form v/vt; all vertices of a face must use the same form"),
      Malformed(
        name: "trailing slash", text: h + "f 1/ 2/ 3/", line: 4, column: 3,
        message:
          "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, found '1/'"
      ),
      Malformed(
        name: "empty normal", text: h + "f 1// 2// 3//", line: 4, column: 3,
        message:
          "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, found '1//'"
      ),
      Malformed(
        name: "leading slash", text: h + "f 1 /2 3", line: 4, column: 5,
        message:
          "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, found '/2'"
      ),
      Malformed(
        name: "four parts", text: h + "f 1/1/1/1 2 3", line: 4, column: 3,
        message:
          "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, found "
          + "'1/1/1/1'"),
    ]
  }()

  /// Each malformed input fails with its exact message, at its exact line
  /// and column, described in the one-line `FILE:LINE:COLUMN: error:` form.
  func testParse_MalformedTable() {
    for entry in Self.malformed {
      do throws(SceneError) {
        _ = try parse(entry.text)
        XCTFail("\(entry.name): parsed without error")
      } catch {
        XCTAssertEqual(error.message, entry.message, entry.name)
        XCTAssertEqual(
          "\(error.line):\(error.column)", "\(entry.line):\(entry.column)",
          entry.name)
        XCTAssertEqual(
          error.description,
          "mesh.obj:\(entry.line):\(entry.column): error: \(entry.message)",
          entry.name)
      }
    }
  }

  /// Bytes that are not UTF-8 are reported, decoded with replacement
  /// characters, rather than trapping or being read as something else.
  func testParse_InvalidUTF8() {
    let bytes: [UInt8] = Array("v 0 0 0\n".utf8) + [0xFF, 0xFE, 0x20, 0x31]
    XCTAssertThrowsError(try OBJReader.parse(bytes: bytes, file: "mesh.obj")) {
      error in
      XCTAssertEqual(
        (error as? SceneError)?.description,
        "mesh.obj:2:1: error: expected a statement keyword (v, vn, vt, f, o, g, s, "
          + "usemtl, mtllib), found '\u{FFFD}\u{FFFD}'")
    }
    let nul: [UInt8] = Array("v 0 0 1".utf8) + [0, 0x20, 0x31, 0x0A]
    XCTAssertThrowsError(try OBJReader.parse(bytes: nul, file: "mesh.obj")) {
      error in
      XCTAssertEqual(
        (error as? SceneError)?.message,
        "expected a number for the z coordinate of 'v', found '1\\u{0}'")
    }
  }

  // MARK: - Robustness

  /// Mutated meshes (words deleted, duplicated or replaced; bytes deleted
  /// or inserted) either parse or throw one well-formed one-line error
  /// pointing inside the text. A trap would end the run. Read in two to
  /// four parts (`parseInParts`), each gives the same mesh or the same
  /// error.
  func testParse_MutatedMeshesNeverTrap() throws {
    let original = Array(
      (Self.elements
        + "f 1 2 3\nf 1/1 2/2 4/3\nf 1//1 3//2 4//3 2//1\nf 2/1/3 3/2/2 4/3/1\n"
        + "# done\ng group\n").utf8)
    let replacements = [
      "f", "v", "vn", "vt", "0", "-1", "-5", "99999999999999999999", "1e999",
      "nan", "1//", "/", "1/1/1/1", "\\", "#", "\u{0}", "é", "\r", "\n",
      "usemtl",
      "l", "2//2", "3/3",
    ]
    var outcomes = (parsed: 0, failed: 0)
    forEachSeed(2000, base: 0x0B1_0001) { generator, seed in
      var bytes = original
      for _ in 0..<Int.random(in: 1...4, using: &generator) {
        mutate(&bytes, replacements: replacements, using: &generator)
      }
      do throws(SceneError) {
        _ = try OBJReader.parse(bytes: bytes, file: "mesh.obj")
        outcomes.parsed += 1
      } catch {
        outcomes.failed += 1
        assertWellFormed(error, in: bytes, seed: seed)
      }
      XCTAssertEqual(
        OBJReaderPartsTests.read(bytes, parts: 2 + Int(seed % 3)),
        OBJReaderPartsTests.read(bytes), "seed \(seed)")
    }
    print("mutated meshes: \(outcomes)")
    // Both outcomes must occur, or the mutations are too weak or too strong.
    XCTAssertGreaterThan(outcomes.parsed, 20)
    XCTAssertGreaterThan(outcomes.failed, 500)
  }

  /// One random edit: a word deleted, duplicated or replaced, or a byte
  /// deleted or inserted.
  private func mutate(
    _ bytes: inout [UInt8], replacements: [String],
    using generator: inout SplitMix64
  ) {
    let words = wordRanges(bytes)
    guard !words.isEmpty else {
      bytes.append(contentsOf: "f".utf8)
      return
    }
    let word = words[Int.random(in: 0..<words.count, using: &generator)]
    switch Int.random(in: 0..<5, using: &generator) {
    case 0:
      bytes.removeSubrange(word)
    case 1:
      bytes.insert(contentsOf: Array(bytes[word]) + [0x20], at: word.lowerBound)
    case 2:
      let replacement = replacements[
        Int.random(in: 0..<replacements.count, using: &generator)]
      bytes.replaceSubrange(word, with: Array(replacement.utf8))
    case 3:
      bytes.remove(at: Int.random(in: 0..<bytes.count, using: &generator))
    default:
      bytes.insert(
        UInt8.random(in: 0...255, using: &generator),
        at: Int.random(in: 0...bytes.count, using: &generator))
    }
  }
}
