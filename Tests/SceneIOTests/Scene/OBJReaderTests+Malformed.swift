import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

extension OBJReaderTests {
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
          "expected a statement keyword (v, vn, vt, f, o, g, s, usemtl, "
            + "mtllib), "
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
          "'cstype' (free-form geometry) is not supported: only polygonal "
            + "faces "
          + "('f') are read"),
      Malformed(
        name: "control character", text: "v\u{1B}x 1", line: 1, column: 1,
        message:
          "expected a statement keyword (v, vn, vt, f, o, g, s, usemtl, "
            + "mtllib), "
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
          "vertex index 0 is invalid: OBJ indices start at 1; "
            + "\(validVertices)"),
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
          "vertex index 1 is out of range: no vertices are defined before "
            + "this face"
      ),
      Malformed(
        name: "huge index", text: h + "f 1 2 99999999999999999999", line: 4,
        column: 7,
        message:
          "vertex index 99999999999999999999 is out of range: "
            + "\(validVertices)"),
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
          "normal index 1 is out of range: no normals are defined before this "
            + "face"
      ),
      Malformed(
        name: "texture index without texture coordinates",
        text: h + "vn 0 0 1\nvn 0 1 0\nf 1/1/1", line: 6, column: 5,
        message:
          "texture coordinate index 1 is out of range: no texture coordinates "
            + "are "
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
          "face vertex '2' has the form v, but the face's first vertex '1//1' "
            + "has "
          + "the form v//vn; all vertices of a face must use the same form"),
      Malformed(
        name: "mixed texture forms", text: h + "vt 0 0\nf 1/1 2/1 3", line: 5,
        column: 11,
        message:
          "face vertex '3' has the form v, but the face's first vertex '1/1' "
            + "has "
          + "the form v/vt; all vertices of a face must use the same form"),
      Malformed(
        name: "trailing slash", text: h + "f 1/ 2/ 3/", line: 4, column: 3,
        message:
          "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, "
            + "found '1/'"
      ),
      Malformed(
        name: "empty normal", text: h + "f 1// 2// 3//", line: 4, column: 3,
        message:
          "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, "
            + "found '1//'"
      ),
      Malformed(
        name: "leading slash", text: h + "f 1 /2 3", line: 4, column: 5,
        message:
          "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, "
            + "found '/2'"
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
        "mesh.obj:2:1: error: expected a statement keyword (v, vn, vt, f, o, "
          + "g, s, "
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
}
