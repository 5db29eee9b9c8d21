import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
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
        + "Lights { numLights 1 DirectionalLight { direction 0 0 -1 color 1 1 "
        + "1 } }\n"
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
      + "Group{numObjects 2 Sphere{center 0 0 0 radius 1}\r\n\tPlane{normal 0 "
      + "0 1 offset -5}}"
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
}
