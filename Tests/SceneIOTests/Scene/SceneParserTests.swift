import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import Numerics
@testable import PlatformSupport
import TestSupport

final class SceneParserTests: XCTestCase {
  /// A one-line camera, so that the lines of each test text are easy to
  /// count: whatever follows it starts on line 2.
  static let camera = Fixtures.camera
  static let sphere = Fixtures.sphere
  static let group = Fixtures.group

  /// Every block, both light kinds (with and without falloff), both
  /// material spellings, nested groups and a non-unit plane normal.
  static let full = """
    # A scene using every block the parser knows.
    PerspectiveCamera {
      center 0 1 10
      direction 0 0 -2
      up 0 3 0
      angle 45
    }
    Lights {
      numLights 3
      PointLight { position 1 2 3  color 1 0.5 0.25  falloff 0.5 }
      PointLight { position -1 -2 -3  color 0.25 0.25 0.25 }
      DirectionalLight { direction 0 -2 0  color 0.5 0.5 0.5 }
    }
    Background { color 0.1 0.2 0.3  ambientLight 0.2 0.2 0.2 }
    Materials {
      numMaterials 3
      Material { diffuseColor 1 0 0 }
      PhongMaterial { diffuseColor 0 1 0  specularColor 1 1 1  shininess 20 }
      PhongMaterial { shininess 2 specularColor 0.5 0.5 0.5 diffuseColor 0 0 1 }
    }
    Group {
      numObjects 4
      Sphere { center 0 0 0  radius 1 }
      MaterialIndex 2
      Plane { normal 0 2 0  offset -4 }
      Group {
        numObjects 2
        Sphere { radius 0.5  center 1 1 1 }
        MaterialIndex 1
        Sphere { center 2 2 2  radius 0.25 }
      }
      Sphere { center 3 3 3  radius 2 }
    }
    """

  func parse(_ text: String) throws(SceneError) -> Scene {
    try SceneParser.parse(text, file: "test.txt")
  }

  // MARK: - Valid scenes

  /// A UTF-8 byte-order mark at the start (as editors on Windows write) is
  /// skipped; columns on the first line count from after it.
  func testParse_ByteOrderMarkSkipped() throws {
    let scene = try parse("\u{FEFF}" + Self.full)
    XCTAssertEqual(scene.camera.center, Vector3(0, 1, 10))
    do {
      _ = try parse("\u{FEFF}PerspectiveCamera { centre 0 0 1 }")
      XCTFail("a misspelt field")
    } catch {
      XCTAssertTrue(
        error.description.hasPrefix("test.txt:1:21: error:"), error.description)
    }
  }

  /// A count beyond the reader's limit says the limit.
  func testParse_CountBeyondTheLimitSaysTheLimit() {
    do {
      _ = try parse(
        "PerspectiveCamera { center 0 0 1 direction 0 0 -1 up 0 1 0 angle 30 }"
          + " Group { numObjects 1000000000000000 }")
      XCTFail("a count past the limit")
    } catch {
      XCTAssertTrue(
        error.description.hasSuffix(
          "'numObjects' must be at most 999999999999999, found "
            + "1000000000000000"), error.description)
    }
  }

  func testParse_EveryBlock() throws {
    let scene = try parse(Self.full)
    XCTAssertEqual(scene.camera.center, Vector3(0, 1, 10))
    XCTAssertEqual(scene.camera.direction, Vector3(0, 0, -1), "normalised")
    XCTAssertEqual(scene.camera.up, Vector3(0, 1, 0))
    XCTAssertEqual(scene.camera.horizontal, Vector3(1, 0, 0))
    XCTAssertEqual(scene.camera.angle, 45)

    XCTAssertEqual(
      scene.lights,
      [
        .point(
          position: Vector3(1, 2, 3), color: Vector3(1, 0.5, 0.25), falloff: 0.5
        ),
        .point(
          position: Vector3(-1, -2, -3), color: Vector3(0.25, 0.25, 0.25),
          falloff: nil),
        .directional(
          direction: Vector3(0, -1, 0), color: Vector3(0.5, 0.5, 0.5)),
      ])
    XCTAssertEqual(scene.background, Vector3(0.1, 0.2, 0.3))
    XCTAssertEqual(scene.ambient, Vector3(0.2, 0.2, 0.2))
    XCTAssertEqual(
      scene.materials,
      [
        Material(diffuse: Vector3(1, 0, 0)),
        Material(
          diffuse: Vector3(0, 1, 0), specular: Vector3(1, 1, 1), shininess: 20),
        Material(
          diffuse: Vector3(0, 0, 1), specular: Vector3(0.5, 0.5, 0.5),
          shininess: 2),
      ])

    // MaterialIndex applies to the objects after it; a nested group starts
    // with its parent's current index, and its own does not leak out.
    let nested = Group<Double>([
      .sphere(Sphere(center: Vector3(1, 1, 1), radius: 0.5, materialIndex: 2)),
      .sphere(Sphere(center: Vector3(2, 2, 2), radius: 0.25, materialIndex: 1)),
    ])
    XCTAssertEqual(
      scene.root,
      Group([
        .sphere(Sphere(center: .zero, radius: 1, materialIndex: 0)),
        .plane(Plane(normal: Vector3(0, 1, 0), offset: -2, materialIndex: 2)),
        .group(nested),
        .sphere(Sphere(center: Vector3(3, 3, 3), radius: 2, materialIndex: 2)),
      ]))
  }

  /// Only the camera and the group are required. Without lights the
  /// ambient light is white (an unlit scene still shows its colours);
  /// the background is black and there is one matte white material.
  func testParse_Defaults() throws {
    let minimal = try parse(Self.camera + Self.group)
    XCTAssertEqual(minimal.lights, [])
    XCTAssertEqual(minimal.ambient, Vector3(1, 1, 1))
    XCTAssertEqual(minimal.background, .zero)
    XCTAssertEqual(minimal.materials, [.defaultWhite])
    XCTAssertEqual(minimal.root.objects.count, 1)

    // A background without ambientLight: still white without lights.
    let backgroundOnly = try parse(
      Self.camera + "Background { color 0.5 0.5 0.5 }\n" + Self.group)
    XCTAssertEqual(backgroundOnly.ambient, Vector3(1, 1, 1))
    XCTAssertEqual(backgroundOnly.background, Vector3(0.5, 0.5, 0.5))

    // With a light and no ambientLight: black ambient.
    let lit = try parse(
      Self.camera
        + "Lights { numLights 1 DirectionalLight { direction 0 0 -1 color 1 1 1 } }\n"
        + Self.group)
    XCTAssertEqual(lit.ambient, .zero)

    // Empty lists are allowed and mean the same as no block.
    let empty = try parse(
      Self.camera + "Lights { numLights 0 }\nMaterials { numMaterials 0 }\n"
        + "Group { numObjects 0 }\n")
    XCTAssertEqual(empty.lights, [])
    XCTAssertEqual(empty.ambient, Vector3(1, 1, 1))
    XCTAssertEqual(empty.materials, [.defaultWhite])
    XCTAssertEqual(empty.root, Group())
  }

  /// `#` starts a comment to the end of the line, also right after a
  /// number or a brace, and at the end of a file without a newline.
  func testParse_Comments() throws {
    let text = """
      # leading comment
      PerspectiveCamera { # after a brace
        center 0 0 10# right after a number
        direction 0 0 -1 up 0 1 0 angle 30 }#after a closing brace
      Group { numObjects 1 Sphere { center 0 0 0 radius 2#radius
      } } # no newline at the end
      """
    let scene = try parse(text)
    XCTAssertEqual(scene.camera.center, Vector3(0, 0, 10))
    XCTAssertEqual(
      scene.root, Group([.sphere(Sphere(center: .zero, radius: 2))]))
  }

  /// Braces are tokens of their own even when they touch words; tabs, CR
  /// and blank lines separate tokens.
  func testParse_BracesTouchingWords() throws {
    let text =
      "PerspectiveCamera{center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30}"
      + "Group{numObjects 2 Sphere{center 0 0 0 radius 1}\r\n\tPlane{normal 0 0 1 offset -5}}"
    let scene = try parse(text)
    XCTAssertEqual(
      scene.root,
      Group([
        .sphere(Sphere(center: .zero, radius: 1)),
        .plane(Plane(normal: Vector3(0, 0, 1), offset: -5)),
      ]))
  }

  /// Non-unit plane normals are normalised with the offset scaled, and
  /// numbers take every decimal form.
  func testParse_PlaneNormalsAndNumberForms() throws {
    let scene = try parse(
      Self.camera + """
        Group { numObjects 3
          Plane { normal 0 0 -4 offset 8 }
          Plane { offset 10 normal 3 4 0 }
          Sphere { center +1. .5 -0 radius 25e-1 }
        }
        """)
    XCTAssertEqual(
      scene.root,
      Group([
        .plane(Plane(normal: Vector3(0, 0, -1), offset: 2)),
        .plane(Plane(normal: Vector3(0.6, 0.8, 0), offset: 2)),
        .sphere(Sphere(center: Vector3(1, 0.5, 0), radius: 2.5)),
      ]))
    if case .sphere(let sphere) = scene.root.objects.last {
      XCTAssertEqual(sphere.center.z.sign, .minus, "-0 keeps its sign")
    }
  }

  /// Exactly `maximumGroupDepth` nested groups are accepted.
  func testParse_MaximumDepth() throws {
    let depth = SceneParser.maximumGroupDepth
    let text =
      Self.camera
      + String(repeating: "Group { numObjects 1\n", count: depth)
      + Self.sphere + String(repeating: " }", count: depth)
    var group = try parse(text).root
    var levels = 1
    while case .group(let inner) = group.objects.first {
      group = inner
      levels += 1
    }
    XCTAssertEqual(levels, depth)
  }

  func testParse_ContentsOfFile() throws {
    let path = FileManager.default.temporaryDirectory
      .appendingPathComponent("raytrace-scene-\(UUID().uuidString).txt").path
    try Data(Self.full.utf8).write(to: URL(fileURLWithPath: path))
    defer { try? FileManager.default.removeItem(atPath: path) }
    let scene = try SceneParser.parse(contentsOf: path)
    XCTAssertEqual(scene.materials.count, 3)

    let missing = path + ".missing"
    XCTAssertThrowsError(try SceneParser.parse(contentsOf: missing)) { error in
      guard let error = error as? SceneError else {
        return XCTFail("\(error) is not a SceneError")
      }
      XCTAssertEqual(error.line, 0, "a problem with the file as a whole")
      XCTAssertEqual(
        error.description,
        "\(missing): error: cannot open the file: No such file or directory")
    }
  }

  /// The file's bytes exactly, read in one call when its size is known.
  func testReadFile_ReadsEveryByte() throws {
    let path = FileManager.default.temporaryDirectory
      .appendingPathComponent("raytrace-bytes-\(UUID().uuidString)").path
    var generator = SplitMix64(seed: 0xF17E)
    for count in [0, 1, 65_536, 200_003] {
      let bytes = (0..<count).map { _ in
        UInt8(truncatingIfNeeded: generator.next())
      }
      try Data(bytes).write(to: URL(fileURLWithPath: path))
      XCTAssertEqual(try readFile(path), bytes, "\(count) bytes")
    }
    try? FileManager.default.removeItem(atPath: path)
  }

  #if os(Linux)
    /// A regular file whose size reads as 0 (as under /proc) is still read
    /// to its end.
    func testReadFile_ReadsPastTheReportedSize() throws {
      let bytes = try readFile("/proc/self/status")
      XCTAssertTrue(String(decoding: bytes, as: UTF8.self).contains("Name:"))
    }
  #endif

  // MARK: - Malformed scenes

  struct Malformed {
    var name: String
    var text: String
    var line: Int
    var column: Int
    var message: String
  }

  static let malformed: [Malformed] = {
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
        line: 3, column: 1, message: "a second 'Lights' block; a scene has one"),

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
          "expected a transform operation or an object, found 'Translat'; did you mean 'Translate'?"
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
          "cannot read 'nowhere.obj': cannot open the file: No such file or directory"
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
          + "Lights { numLights 2\nDirectionalLight { direction 0 0 -1 color 1 1 1 }\n}",
        line: 4, column: 1,
        message: "Lights has 1 light but numLights (line 2) says 2"),
      Malformed(
        name: "Lights with too many lights",
        text: c
          + "Lights { numLights 0\n  PointLight { position 0 0 0 color 1 1 1 } }",
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

      // Fields.
      Malformed(
        name: "missing field",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 } }",
        line: 2, column: 44, message: "Sphere is missing 'radius'"),
      Malformed(
        name: "missing fields",
        text: "PerspectiveCamera {\n center 0 0 0\n up 0 1 0\n}\n" + g, line: 4,
        column: 1,
        message: "PerspectiveCamera is missing 'direction' and 'angle'"),
      Malformed(
        name: "missing diffuse colour",
        text: c + "Materials { numMaterials 1 PhongMaterial { shininess 3 } }",
        line: 2, column: 56, message: "PhongMaterial is missing 'diffuseColor'"),
      Malformed(
        name: "missing light colour",
        text: c + "Lights { numLights 1 PointLight { position 0 0 0 } }",
        line: 2, column: 50, message: "PointLight is missing 'color'"),
      Malformed(
        name: "field given twice",
        text: c
          + "Group { numObjects 1 Sphere { radius 1 center 0 0 0 radius 2 } }",
        line: 2, column: 53, message: "'radius' is given twice in Sphere"),
      Malformed(
        name: "duplicate camera field",
        text: "PerspectiveCamera { angle 30 angle 40 }", line: 1, column: 30,
        message: "'angle' is given twice in PerspectiveCamera"),
      Malformed(
        name: "unknown field with suggestion",
        text: c + "Group { numObjects 1 Sphere { centre 0 0 0 radius 1 } }",
        line: 2, column: 31,
        message:
          "expected a field of Sphere, found 'centre'; did you mean 'center'?"),
      Malformed(
        name: "unknown light with suggestion",
        text: c + "Lights { numLights 1 SpotLight { } }", line: 2, column: 22,
        message:
          "expected a light, found 'SpotLight'; did you mean 'PointLight'?"),
      Malformed(
        name: "object among the lights",
        text: c + "Lights { numLights 1 \(s) }", line: 2, column: 22,
        message: "expected a light, found 'Sphere' (expected one of "
          + "'PointLight', 'DirectionalLight')"),
      Malformed(
        name: "unknown material with suggestion",
        text: c + "Materials { numMaterials 1 PhongMaterail { } }", line: 2,
        column: 28,
        message:
          "expected a material, found 'PhongMaterail'; did you mean 'PhongMaterial'?"
      ),
      Malformed(
        name: "number for an object", text: c + "Group { numObjects 1 5 }",
        line: 2, column: 22, message: "expected an object, found the number 5"),
      Malformed(
        name: "brace inside a group", text: c + "Group { numObjects 0 { } }",
        line: 2, column: 22, message: "unexpected '{' in Group"),

      // Numbers.
      Malformed(
        name: "number expected",
        text: c + "Group { numObjects 1 Sphere { center 0 zero 0 radius 1 } }",
        line: 2, column: 40, message: "expected a number, found 'zero'"),
      Malformed(
        name: "number cut short by a brace",
        text: c + "Group { numObjects 1 Sphere { center 0 0 } }",
        line: 2, column: 42, message: "expected a number, found '}'"),
      Malformed(
        name: "hexadecimal is not decimal",
        text: c + "Group { numObjects 1 Sphere { center 0x10 0 0 radius 1 } }",
        line: 2, column: 38, message: "expected a number, found '0x10'"),
      Malformed(
        name: "nan",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 radius nan } }",
        line: 2, column: 51, message: "expected a finite number, found 'nan'"),
      Malformed(
        name: "inf", text: "PerspectiveCamera { center -inf 0 0 }", line: 1,
        column: 28,
        message: "expected a finite number, found '-inf'"),
      Malformed(
        name: "overflowing literal",
        text: "PerspectiveCamera { center 0 0 0 angle 1e999 }", line: 1,
        column: 40,
        message:
          "'1e999' is beyond the finite range of double "
          + "(±1.7976931348623157e+308)"),
      Malformed(
        name: "zero radius",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 radius 0 } }",
        line: 2, column: 51, message: "'radius' must be positive, found 0"),
      Malformed(
        name: "negative radius",
        text: c + "Group { numObjects 1 Sphere { radius -2.5 center 0 0 0 } }",
        line: 2, column: 38, message: "'radius' must be positive, found -2.5"),
      Malformed(
        name: "zero plane normal",
        text: c + "Group { numObjects 1 Plane { normal 0 0 0 offset 1 } }",
        line: 2, column: 37, message: "'normal' must not be the zero vector"),
      Malformed(
        name: "zero light direction",
        text: c
          + "Lights { numLights 1 DirectionalLight { direction 0 0 0 color 1 1 1 } }",
        line: 2, column: 51, message: "'direction' must not be the zero vector"),
      Malformed(
        name: "negative colour",
        text: c + "Background { color 0 -0.5 0 }", line: 2, column: 20,
        message: "'color' components must not be negative"),
      Malformed(
        name: "zero falloff",
        text: c
          + "Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1 falloff 0 } }",
        line: 2, column: 70, message: "'falloff' must be positive, found 0"),
      Malformed(
        name: "negative shininess",
        text: c
          + "Materials { numMaterials 1 Material { diffuseColor 1 1 1 shininess -1 } }",
        line: 2, column: 68,
        message: "'shininess' must not be negative, found -1"),

      // The camera.
      Malformed(
        name: "camera angle 0",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 0 -1 up 0 1 0 angle 0 }",
        line: 1, column: 66,
        message: "the camera's angle must be between 0 and 180 degrees, found 0"
      ),
      Malformed(
        name: "camera angle 180",
        text:
          "PerspectiveCamera {\n angle 180 center 0 0 0 direction 0 0 -1 up 0 1 0 }",
        line: 2, column: 8,
        message:
          "the camera's angle must be between 0 and 180 degrees, found 180"),
      Malformed(
        name: "zero camera direction",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 0 0 up 0 1 0 angle 30 }",
        line: 1, column: 44, message: "the camera's direction must not be zero"),
      Malformed(
        name: "up parallel to direction",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 1 0 up 0 -2 0 angle 30 }",
        line: 1, column: 53,
        message:
          "the camera's up vector must not be zero or parallel to its direction"
      ),
      Malformed(
        name: "zero up",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 1 0 up 0 0 0 angle 30 }",
        line: 1, column: 53,
        message:
          "the camera's up vector must not be zero or parallel to its direction"
      ),

      // Material indices, checked once the materials are known.
      Malformed(
        name: "MaterialIndex out of range",
        text: c + "Materials { numMaterials 2 Material { diffuseColor 1 1 1 }\n"
          + "Material { diffuseColor 1 1 1 } }\nGroup { numObjects 1\n"
          + "  MaterialIndex 2 \(s) }",
        line: 5, column: 17,
        message:
          "MaterialIndex 2 is out of range: the scene has 2 materials (0 to 1)"),
      Malformed(
        name: "MaterialIndex out of range, materials after the group",
        text: c + "Group { numObjects 1 MaterialIndex 1 \(s) }\n"
          + "Materials { numMaterials 1 Material { diffuseColor 1 1 1 } }",
        line: 2, column: 36,
        message:
          "MaterialIndex 1 is out of range: the scene has 1 material (0 to 0)"),
      Malformed(
        name: "MaterialIndex out of range in a nested group, no materials",
        text: c
          + "Group { numObjects 1\n Group { numObjects 1\n  MaterialIndex 1 \(s) } }",
        line: 4, column: 17,
        message: "MaterialIndex 1 is out of range: the scene has no materials "
          + "(only the default, 0)"),
      Malformed(
        name: "fractional MaterialIndex",
        text: c + "Group { numObjects 1 MaterialIndex 0.5 \(s) }", line: 2,
        column: 36,
        message: "'MaterialIndex' must be a whole number ≥ 0, found 0.5"),

      // Ends of file.
      Malformed(
        name: "unterminated group",
        text: c + "Group { numObjects 1\n  \(s)\n", line: 4, column: 1,
        message: "unexpected end of file: Group is missing its '}'"),
      Malformed(
        name: "unterminated sphere",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 radius 1",
        line: 2, column: 52,
        message: "unexpected end of file: Sphere is missing its '}'"),
      Malformed(
        name: "unterminated lights", text: c + "Lights { numLights 0 ", line: 2,
        column: 22,
        message: "unexpected end of file: Lights is missing its '}'"),
      Malformed(
        name: "end of file inside a vector",
        text: "PerspectiveCamera { center 0 0", line: 1, column: 31,
        message: "expected a number, found 'end of file'"),

      // Nesting: one level more than the limit, of groups alone or of
      // transforms inside a group, fails at the level past it.
    ]
      + [
        ("nesting beyond the maximum depth", "Group { numObjects 1\n"),
        (
          "transforms nested beyond the maximum depth",
          "Transform { Translate 0 0 0\n"
        ),
      ].map { name, level in
        let depth = SceneParser.maximumGroupDepth
        return Malformed(
          name: name,
          text: c + "Group { numObjects 1\n"
            + String(repeating: level, count: depth) + s
            + String(repeating: " }", count: depth + 1),
          line: depth + 2, column: 1,
          message: "Groups and Transforms are nested more than \(depth) deep")
      }
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

  // MARK: - Robustness

  /// Mutated scenes (tokens deleted, duplicated, swapped or replaced;
  /// bytes deleted or inserted) either parse or throw one well-formed
  /// one-line error pointing inside the text. A trap would end the run.
  func testParse_MutatedScenesNeverTrap() throws {
    let original = Array(Self.full.utf8)
    let replacements = [
      "{", "}", "Group", "Sphere", "Plane", "MaterialIndex", "numObjects", "-1",
      "0",
      "1e999", "nan", "-inf", "1e-400", "0.5", "99999999999999999999",
      "PerspectiveCamera",
      "Transform", "#", "é", "\u{0}", "Materials", "numMaterials", "180",
      "radius",
    ]
    var outcomes = (parsed: 0, failed: 0)
    forEachSeed(2000, base: 0xF022_0001) { generator, seed in
      var bytes = original
      for _ in 0..<Int.random(in: 1...4, using: &generator) {
        mutate(&bytes, replacements: replacements, using: &generator)
      }
      let text = String(decoding: bytes, as: UTF8.self)
      do throws(SceneError) {
        _ = try parse(text)
        outcomes.parsed += 1
      } catch {
        outcomes.failed += 1
        assertWellFormed(error, in: Array(text.utf8), seed: seed)
      }
    }
    print("mutated scenes: \(outcomes)")
    // Both outcomes must occur, or the mutations are too weak or too strong.
    XCTAssertGreaterThan(outcomes.parsed, 20)
    XCTAssertGreaterThan(outcomes.failed, 1000)
  }

  /// A large group read on two threads gives the sequential parse's scene
  /// or error, to the line and column, whatever the file: mutated scenes
  /// of spheres, material indices, comments, a nested group, a transform
  /// and a plane, split near their middle.
  func testParse_GroupReadOnTwoThreads_MatchesOneThread() throws {
    var lines = [
      Self.camera.trimmingCharacters(in: .newlines),
      "Materials { numMaterials 3 Material { diffuseColor 1 0 0 }",
      "  Material { diffuseColor 0 1 0 } Material { diffuseColor 0 0 1 } }",
      "Group {", "  numObjects 57", "  MaterialIndex 1",
    ]
    for index in 0..<60 {
      switch index {
      case 5:
        lines.append(
          "  Group { numObjects 1 Sphere { center 0 0 1 radius 2 } }")
      case 8:
        lines.append(
          "  Transform { Translate 1 0 0 Sphere { radius 1 center 0 0 0 } }")
      case 10: lines.append("  Plane { normal 0 1 0 offset -2 }")
      case 12: lines.append("  MaterialIndex 2  # a comment {")
      case 45: lines.append("  MaterialIndex 0")
      case 50: lines.append("  # Sphere { center")
      default:
        lines.append(
          "  Sphere { center \(index) -\(index).5 0.25  radius 0.\(index + 1) }"
        )
      }
    }
    lines.append("}")
    let original = Array(lines.joined(separator: "\n").utf8)
    let replacements = [
      "{", "}", "Group", "Sphere", "MaterialIndex", "7", "-1", "nan", "#",
      "radius", "center", "numObjects", "\n",
    ]
    var outcomes = (parsed: 0, failed: 0, spliced: 0)
    let seeds = Self.seedCount(1500)
    forEachSeed(seeds, base: 0x2_7EAD) { generator, seed in
      var bytes = original
      if seed != 0x2_7EAD {
        for _ in 0..<Int.random(in: 1...3, using: &generator) {
          mutate(&bytes, replacements: replacements, using: &generator)
        }
      }
      let one: Result<Scene, SceneError>
      let two: Result<Scene, SceneError>
      var spliced = 0
      do throws(SceneError) {
        one = .success(try SceneParser.parse(bytes: bytes, file: "t.txt"))
      } catch {
        one = .failure(error)
      }
      do throws(SceneError) {
        two = .success(
          try SceneParser.parse(
            bytes: bytes, file: "t.txt", concurrentFrom: (1, 1),
            spliced: &spliced))
      } catch {
        two = .failure(error)
      }
      if spliced > 0 { outcomes.spliced += 1 }
      if seed == 0x2_7EAD {
        XCTAssertGreaterThan(spliced, 10, "the unmutated scene is split")
      }
      switch (one, two) {
      case (.success(let one), .success(let two)):
        outcomes.parsed += 1
        XCTAssertEqual(one.root, two.root, "seed \(seed)")
      case (.failure(let one), .failure(let two)):
        outcomes.failed += 1
        XCTAssertEqual(one, two, "seed \(seed)")
      default:
        XCTFail("seed \(seed): \(one) against \(two)")
      }
    }
    print("group read on two threads: \(outcomes)")
    // Of 1500 seeds (RAYTRACE_LONG_TESTS) more than 100, 300 and 300.
    XCTAssertGreaterThan(outcomes.parsed, seeds / 15)
    XCTAssertGreaterThan(outcomes.failed, seeds / 5)
    XCTAssertGreaterThan(outcomes.spliced, seeds / 5)
  }

  private func mutate(
    _ bytes: inout [UInt8], replacements: [String],
    using generator: inout SplitMix64
  ) {
    let tokens = wordRanges(bytes)
    guard !tokens.isEmpty, !bytes.isEmpty else {
      bytes.append(contentsOf: "Group".utf8)
      return
    }
    let token = tokens[Int.random(in: 0..<tokens.count, using: &generator)]
    switch Int.random(in: 0..<6, using: &generator) {
    case 0:
      bytes.removeSubrange(token)
    case 1:
      bytes.insert(
        contentsOf: Array(bytes[token]) + [0x20], at: token.lowerBound)
    case 2:
      let replacement = replacements[
        Int.random(in: 0..<replacements.count, using: &generator)]
      bytes.replaceSubrange(token, with: Array(replacement.utf8))
    case 3:
      let other = tokens[Int.random(in: 0..<tokens.count, using: &generator)]
      if other.lowerBound > token.upperBound {
        let (first, second) = (Array(bytes[token]), Array(bytes[other]))
        bytes.replaceSubrange(other, with: first)
        bytes.replaceSubrange(token, with: second)
      }
    case 4:
      bytes.remove(at: Int.random(in: 0..<bytes.count, using: &generator))
    default:
      bytes.insert(
        UInt8.random(in: 0...255, using: &generator),
        at: Int.random(in: 0...bytes.count, using: &generator))
    }
  }

  // MARK: - Rotate and textures

  /// `Rotate ax ay az deg` turns about any axis, right-handed: about z it
  /// is ZRotate, about (1, 1, 1) a third of a turn maps x onto y.
  func testTransform_RotateAboutAxis() throws {
    func root(_ operation: String) throws -> Group<Double> {
      try parse(
        Self.camera + "Group { numObjects 1 Transform { \(operation) "
          + "Sphere { center 1 0 0 radius 0.5 } } }"
      ).root
    }
    XCTAssertEqual(
      try root("Rotate 0 0 2 30").flattened().spheres.first?.center ?? .zero,
      try root("ZRotate 30").flattened().spheres.first?.center ?? .zero)
    let turned = try XCTUnwrap(
      try root("Rotate 1 1 1 120").flattened().spheres.first?.center)
    XCTAssertLessThan((turned - Vector3(0, 1, 0)).maxMagnitude, 4e-16)
    XCTAssertThrowsError(try root("Rotate 0 0 0 30")) { error in
      XCTAssertEqual(
        (error as? SceneError)?.description,
        "test.txt:2:41: error: 'Rotate' needs a non-zero axis")
    }
  }

  /// `texture PATH` is relative to the scene's folder; a textured material
  /// on a mesh without texture coordinates is an error at the mesh.
  func testMaterial_TextureAndMeshWithoutCoordinates() throws {
    let folder = NSTemporaryDirectory() + "texture-\(UUID().uuidString)"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
    defer { try? FileManager.default.removeItem(atPath: folder) }
    try "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".write(
      toFile: "\(folder)/plain.obj", atomically: true, encoding: .utf8)
    let materials =
      "Materials { numMaterials 1 Material { diffuseColor 1 1 1 "
      + "texture wood.bmp } }\n"
    let scene = try SceneParser.parse(
      Self.camera + materials + Self.group, file: "\(folder)/s.txt")
    XCTAssertEqual(scene.materials[0].texturePath, "\(folder)/wood.bmp")
    XCTAssertThrowsError(
      try SceneParser.parse(
        Self.camera + materials
          + "Group { numObjects 1 TriangleMesh { obj_file plain.obj } }",
        file: "\(folder)/s.txt")
    ) { error in
      XCTAssertEqual(
        (error as? SceneError)?.description,
        "\(folder)/s.txt:3:46: error: material 0 has a texture, but the "
          + "mesh '\(folder)/plain.obj' has no texture coordinates (no face "
          + "gives vt)")
    }
  }
}
