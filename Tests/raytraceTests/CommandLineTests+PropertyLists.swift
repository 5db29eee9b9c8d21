import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension CommandLineTests {
  // MARK: - The course's property lists and textures

  /// A plist scene is recognised by its content, whatever its name, and
  /// renders the bytes of the same scene in text.
  func testRender_PlistByContent() throws {
    let copy = folder + "/scene.txt"
    try FileManager.default.copyItem(
      atPath: Self.packageRoot + "/scenes/spheres.plist", toPath: copy)
    try run([
      "scenes/spheres.txt", "--size", "32", "24", "-o", folder + "/t.png",
    ])
    let outcome = try run([copy, "--size", "32", "24", "-o", folder + "/p.png"])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    XCTAssertEqual(try read("t.png"), try read("p.png"))
  }

  /// `--engine course` draws the default engine's image, says so in the
  /// stats, and refuses Float (it computes in the scene's Double).
  func testEngine_CourseDrawsTheSameImage() throws {
    let scene = "scenes/mesh-and-transforms.txt"
    try run([scene, "--size", "32", "24", "-o", folder + "/fast.png"])
    let course = try run([
      scene, "--size", "32", "24", "-o", folder + "/course.png", "--engine",
      "course", "--stats",
    ])
    XCTAssertEqual(course.status, 0, course.stderr)
    XCTAssertTrue(course.stderr.contains("engine course"), course.stderr)
    XCTAssertEqual(try read("fast.png"), try read("course.png"))
    let float = try run([
      scene, "-o", folder + "/f.png", "--engine", "course", "--precision",
      "float",
    ])
    XCTAssertEqual(float.status, 64, float.stderr)
    XCTAssertTrue(float.stderr.contains("--engine course"), float.stderr)
  }

  /// Textures are read only for a shaded image, and the stats say so; an
  /// unreadable texture is one line naming it, exit 1, nothing written.
  func testTextures_ReadOnlyWhenShaded() throws {
    let scene = "scenes/textured.txt"
    let depth = try run([
      scene, "--size", "16", "12", "--depth", folder + "/d.png", "--stats",
    ])
    XCTAssertEqual(depth.status, 0, depth.stderr)
    XCTAssertTrue(
      depth.stderr.contains(
        "textures: none read (no shaded image is requested)"),
      depth.stderr)
    let shaded = try run([
      scene, "--size", "16", "12", "-o", folder + "/s.png", "--stats",
    ])
    XCTAssertTrue(
      shaded.stderr.contains("textures: 2 read for the shaded image"),
      shaded.stderr)

    let text = try String(
      contentsOfFile: Self.packageRoot + "/" + scene, encoding: .utf8)
    try FileManager.default.createDirectory(
      atPath: folder + "/Meshes", withIntermediateDirectories: true)
    for mesh in ["crate", "floor"] {
      try FileManager.default.copyItem(
        atPath: Self.packageRoot + "/scenes/Meshes/\(mesh).obj",
        toPath: folder + "/Meshes/\(mesh).obj")
    }
    try text.write(
      toFile: folder + "/t.txt", atomically: true, encoding: .utf8)
    let missing = try run([folder + "/t.txt", "-o", folder + "/m.png"])
    XCTAssertEqual(missing.status, 1)
    XCTAssertEqual(
      missing.stderr,
      "\(folder)/Textures/crate.bmp: error: cannot read the texture: cannot "
        + "open the file: No such file or directory\n")
    XCTAssertFalse(files().contains("m.png"))
    let depthOnly = try run([
      folder + "/t.txt", "--size", "16", "12", "--depth", folder + "/d2.png",
    ])
    XCTAssertEqual(depthOnly.status, 0, "depth never opens a texture")
  }

  /// A plist error: one line with the key path, exit 1.
  func testSceneError_PlistKeyPath() throws {
    let path = folder + "/bad.plist"
    try """
    <?xml version="1.0" encoding="UTF-8"?>
    <plist version="1.0"><dict><key>Camera</key><dict>
    <key>center</key><string>0 0</string></dict></dict></plist>
    """.write(toFile: path, atomically: true, encoding: .utf8)
    let outcome = try run([path, "-o", folder + "/x.png"])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr,
      "\(path): error: Camera.center: expected 3 numbers, found \"0 0\"\n")
  }
}
