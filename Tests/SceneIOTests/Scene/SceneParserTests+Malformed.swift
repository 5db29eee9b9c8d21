import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

extension SceneParserTests {
  // MARK: - Malformed scenes

  struct Malformed {
    var name: String
    var text: String
    var line: Int
    var column: Int
    var message: String
  }

  static let malformed: [Malformed] = malformedStructure + malformedValues

  /// Malformed files as a whole, block names and counts.
  static let malformedStructure: [Malformed] = {
    let c = SceneParserTests.camera
    let g = SceneParserTests.group
    let s = SceneParserTests.sphere
    return [
      // Files as a whole.
      Malformed(
        name: "empty file", text: "", line: 1, column: 1,
        message: "the scene has no PerspectiveCamera"),
      Malformed(
        name: "only a comment", text: "# nothing here\n", line: 2, column: 1,
        message: "the scene has no PerspectiveCamera"),
      Malformed(
        name: "missing camera", text: "\n  " + g, line: 2, column: 3,
        message: "the scene has no PerspectiveCamera"),
      Malformed(
        name: "missing group", text: c, line: 1, column: 1,
        message: "the scene has no Group"),
      Malformed(
        name: "second camera", text: c + g + "  " + c, line: 3, column: 3,
        message: "a second 'PerspectiveCamera' block; a scene has one"),
      Malformed(
        name: "second group", text: c + g + g, line: 3, column: 1,
        message: "a second 'Group' block; a scene has one"),
      Malformed(
        name: "second lights",
        text: c + "Lights { numLights 0 }\nLights { numLights 0 }",
        line: 3, column: 1,
        message: "a second 'Lights' block; a scene has one"),

      // Block names.
      Malformed(
        name: "unknown block with suggestion",
        text: c + "Lihgts { numLights 0 }",
        line: 2, column: 1,
        message: "expected a block name, found 'Lihgts'; did you mean 'Lights'?"
      ),
      Malformed(
        name: "block name in the wrong case",
        text: c + "group { numObjects 0 }",
        line: 2, column: 1,
        message: "expected a block name, found 'group'; did you mean 'Group'?"),
      Malformed(
        name: "unknown block without suggestion", text: c + "Teapot { }",
        line: 2, column: 1,
        message: "expected a block name, found 'Teapot' (expected one of "
          + "'PerspectiveCamera', 'Lights', 'Background', 'Materials', 'Group')"
      ),
      Malformed(
        name: "number for a block", text: c + "42", line: 2, column: 1,
        message: "expected a block name, found the number 42"),
      Malformed(
        name: "stray closing brace", text: c + "}", line: 2, column: 1,
        message: "expected a block name, found '}'"),
      Malformed(
        name: "Transform without an object",
        text: c + "Group { numObjects 1\n  Transform { } }",
        line: 3, column: 15, message: "Transform has no object to transform"),
      Malformed(
        name: "Transform with two objects",
        text: c
          + "Group { numObjects 1\n  Transform { Translate 1 0 0 \(s) \(s) } }",
        line: 3, column: 64,
        message: "a Transform holds one object; group several in a Group"),
      Malformed(
        name: "Transform operation after the object",
        text: c + "Group { numObjects 1 Transform { \(s) Scale 2 2 2 } }",
        line: 2, column: 67,
        message: "transform operations come before the object, found 'Scale'"),
      Malformed(
        name: "Transform scale of zero",
        text: c + "Group { numObjects 1 Transform { Scale 1 0 1 \(s) } }",
        line: 2, column: 40, message: "'Scale' factors must not be 0"),
      Malformed(
        name: "misspelt transform operation",
        text: c + "Group { numObjects 1 Transform { Translat 1 0 0 \(s) } }",
        line: 2, column: 34,
        message:
          "expected a transform operation or an object, found 'Translat'; did "
            + "you mean 'Translate'?"
      ),
      Malformed(
        name: "TriangleMesh without its file",
        text: c + "Group { numObjects 1 TriangleMesh { } }",
        line: 2, column: 37, message: "TriangleMesh is missing 'obj_file'"),
      Malformed(
        name: "TriangleMesh whose file does not exist",
        text: c
          + "Group { numObjects 1 TriangleMesh { obj_file nowhere.obj } }",
        line: 2, column: 46,
        message:
          "cannot read 'nowhere.obj': cannot open the file: No such file or "
            + "directory"
      ),
      Malformed(
        name: "Triangle missing a vertex",
        text: c
          + "Group { numObjects 1 Triangle { vertex0 0 0 0 vertex1 1 0 0 } }",
        line: 2, column: 61, message: "Triangle is missing 'vertex2'"),
      Malformed(
        name: "OrthographicCamera", text: "OrthographicCamera { }", line: 1,
        column: 1,
        message:
          "'OrthographicCamera' is not supported: raytrace's one camera is "
          + "PerspectiveCamera"),
      Malformed(
        name: "a procedural material",
        text: c + "Materials { numMaterials 1 "
          + "Marble { } }", line: 2, column: 28,
        message:
          "'Marble' is not supported: raytrace's materials are Material and "
          + "PhongMaterial, with an image as an optional texture"),
      Malformed(
        name: "a shape of a later assignment",
        text: c + "Group { numObjects 1 Box { } }", line: 2, column: 22,
        message:
          "'Box' is not supported: raytrace's shapes are Sphere, Plane, "
          + "Triangle and TriangleMesh, in Groups and Transforms (a shape of "
          + "your own: docs/ADDING-A-SHAPE.md)"),
      Malformed(
        name: "missing brace", text: c + "Group numObjects 0 }", line: 2,
        column: 7,
        message: "expected '{' after Group, found 'numObjects'"),
      Malformed(
        name: "missing brace at end", text: c + "Background", line: 2,
        column: 11,
        message: "expected '{' after Background, found end of file"),

      // Counts.
      Malformed(
        name: "Group with too few objects",
        text: c + "Group {\n numObjects 2\n \(s)\n}", line: 5, column: 1,
        message: "Group has 1 object but numObjects (line 3) says 2"),
      Malformed(
        name: "Group with too many objects",
        text: c + "Group { numObjects 1\n \(s)\n \(s) }", line: 4, column: 2,
        message: "Group has more objects than numObjects (line 2) says (1)"),
      Malformed(
        name: "Lights with too few lights",
        text: c
          + "Lights { numLights 2\nDirectionalLight { direction 0 0 -1 color "
          + "1 1 1 }\n}",
        line: 4, column: 1,
        message: "Lights has 1 light but numLights (line 2) says 2"),
      Malformed(
        name: "Lights with too many lights",
        text: c
          + "Lights { numLights 0\n  PointLight { position 0 0 0 color 1 1 1 "
          + "} }",
        line: 3, column: 3,
        message: "Lights has more lights than numLights (line 2) says (0)"),
      Malformed(
        name: "Materials with too few materials",
        text: c
          + "Materials { numMaterials 3 Material { diffuseColor 1 1 1 } }",
        line: 2, column: 60,
        message: "Materials has 1 material but numMaterials (line 2) says 3"),
      Malformed(
        name: "Materials with too many materials",
        text: c
          + "Materials {\nnumMaterials 1\nMaterial { diffuseColor 1 1 1 }\n"
          + "PhongMaterial { diffuseColor 1 1 1 } }",
        line: 5, column: 1,
        message:
          "Materials has more materials than numMaterials (line 3) says (1)"),
      Malformed(
        name: "count field missing", text: c + "Group { \(s) }", line: 2,
        column: 9,
        message: "expected 'numObjects' at the start of Group, found 'Sphere'"),
      Malformed(
        name: "negative count", text: c + "Lights { numLights -1 }", line: 2,
        column: 20,
        message: "'numLights' must be a whole number ≥ 0, found -1"),
      Malformed(
        name: "fractional count", text: c + "Materials { numMaterials 1.5 }",
        line: 2, column: 26,
        message: "'numMaterials' must be a whole number ≥ 0, found 1.5"),
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
        XCTAssertEqual(error.file, "test.txt", entry.name)
        XCTAssertEqual(
          error.description,
          "test.txt:\(entry.line):\(entry.column): error: \(entry.message)",
          entry.name)
      }
    }
  }
}
