import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// A text scene names a mesh or a texture by its path; when the path names
/// no file, by name as a property list does (`Meshes/NAME.obj`,
/// `Textures/NAME.bmp`), so that a course scene written out in the text
/// format finds the course's folders as they are.
final class ResourceLookupTests: XCTestCase {
  static let triangle =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
    + "f 1/1 2/2 3/3\n"
  static let twoTriangles = triangle + "f 1/1 3/3 2/2\n"

  var folder = ""

  override func setUpWithError() throws {
    folder = NSTemporaryDirectory() + "resource-lookup-\(UUID().uuidString)"
    for sub in ["Meshes", "Textures"] {
      try FileManager.default.createDirectory(
        atPath: folder + "/" + sub, withIntermediateDirectories: true)
    }
  }

  override func tearDownWithError() throws {
    try? FileManager.default.removeItem(atPath: folder)
  }

  func write(_ text: String, _ name: String) throws {
    try text.write(
      toFile: folder + "/" + name, atomically: true, encoding: .utf8)
  }

  /// The scene's mesh, read from `obj_file MESH` with a material whose
  /// texture is `TEXTURE`.
  func read(mesh: String, texture: String) throws -> Scene {
    try write(
      """
      PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }
      Materials { numMaterials 1
        PhongMaterial { diffuseColor 1 1 1 texture \(texture) } }
      Group { numObjects 1 MaterialIndex 0 TriangleMesh { obj_file \(mesh) } }
      """, "s.txt")
    return try SceneReader.read(
      contentsOf: folder + "/s.txt", options: SceneOptions(style: .course))
  }

  func triangles(_ scene: Scene) -> Int {
    guard case .mesh(let mesh)? = scene.root.objects.first else { return -1 }
    return mesh.count
  }

  func testNames_FoundAsThePropertyListsFindThem() throws {
    try write(Self.triangle, "Meshes/crate.obj")
    try write("not read while parsing", "Textures/wood.bmp")
    let scene = try read(mesh: "crate", texture: "wood")
    XCTAssertEqual(triangles(scene), 1)
    XCTAssertEqual(scene.meshFiles, [folder + "/Meshes/crate.obj"])
    XCTAssertEqual(
      scene.materials.first?.texturePath, folder + "/Textures/wood.bmp")
  }

  /// A path that names a file is that file, whatever the folders hold.
  func testPaths_WinOverNames() throws {
    try write(Self.triangle, "Meshes/crate.obj")
    try write(Self.twoTriangles, "crate")
    try write("", "Textures/wood.bmp")
    try write("", "wood")
    let scene = try read(mesh: "crate", texture: "wood")
    XCTAssertEqual(triangles(scene), 2)
    XCTAssertEqual(scene.materials.first?.texturePath, folder + "/wood")
  }

  /// Neither a file nor a name: the error names the path as written.
  func testNeither_TheErrorNamesThePathAsWritten() throws {
    XCTAssertThrowsError(try read(mesh: "nothing", texture: "wood")) {
      error in
      let message = (error as? SceneError)?.description ?? "\(error)"
      XCTAssertTrue(message.contains("s.txt:4:"), message)
      XCTAssertTrue(
        message.contains("cannot read '\(self.folder)/nothing': "), message)
    }
  }
}
