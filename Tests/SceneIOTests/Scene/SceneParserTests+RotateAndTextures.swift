import FastKernels
import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

extension SceneParserTests {
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
