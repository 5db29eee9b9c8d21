import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// A mesh file a scene names many times is read once: every use shares
/// the arrays, each with its own material.
final class MeshLoaderTests: XCTestCase {
  func testOneFileNamedThreeTimes_ReadOnce() throws {
    let folder = NSTemporaryDirectory() + "mesh-loader-\(UUID().uuidString)"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
    defer { try? FileManager.default.removeItem(atPath: folder) }
    try "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".write(
      toFile: folder + "/m.obj", atomically: true, encoding: .utf8)
    let scene = """
      PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }
      Materials { numMaterials 2 PhongMaterial { diffuseColor 1 0 0 }
        PhongMaterial { diffuseColor 0 1 0 } }
      Group { numObjects 3
        MaterialIndex 0 TriangleMesh { obj_file m.obj }
        MaterialIndex 1 TriangleMesh { obj_file m.obj }
        Transform { Translate 1 0 0 TriangleMesh { obj_file m.obj } } }
      """
    try scene.write(
      toFile: folder + "/s.txt", atomically: true, encoding: .utf8)
    let read = try SceneReader.read(
      contentsOf: folder + "/s.txt", options: SceneOptions(style: .course))
    var meshes: [TriangleMesh<Double>] = []
    for object in read.root.objects {
      switch object {
      case .mesh(let mesh): meshes.append(mesh)
      case .transform(let transform):
        if case .mesh(let mesh) = transform.object { meshes.append(mesh) }
      default: break
      }
    }
    XCTAssertEqual(meshes.count, 3)
    XCTAssertEqual(meshes.map(\.materialIndex), [0, 1, 1])
    let addresses = meshes.map {
      $0.vertices.withUnsafeBufferPointer { $0.baseAddress }
    }
    XCTAssertEqual(Set(addresses).count, 1, "one array of vertices for all")
    XCTAssertEqual(Set(meshes.map(\.storage.identity)).count, 1)
  }

  /// A mesh file too large for the process's memory (a sparse file of
  /// 100 GiB) is refused from its size, before anything is read.
  func testMeshTooLargeForMemory_RefusedBeforeReading() throws {
    let folder = NSTemporaryDirectory() + "mesh-large-\(UUID().uuidString)"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
    defer { try? FileManager.default.removeItem(atPath: folder) }
    let descriptor = open(folder + "/big.obj", O_WRONLY | O_CREAT, 0o644)
    XCTAssertGreaterThanOrEqual(descriptor, 0)
    XCTAssertEqual(ftruncate(descriptor, 100 << 30), 0)
    close(descriptor)
    let scene = """
      PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }
      Group { numObjects 1 TriangleMesh { obj_file big.obj } }
      """
    try scene.write(
      toFile: folder + "/s.txt", atomically: true, encoding: .utf8)
    let start = Date()
    XCTAssertThrowsError(
      try SceneReader.read(
        contentsOf: folder + "/s.txt", options: SceneOptions(style: .course))
    ) { error in
      let message = (error as? SceneError)?.message ?? ""
      XCTAssertTrue(
        message.contains(
          "big.obj' would need about 600.0 GiB once read, and the process may "
            + "use at most"
        ),
        message)
    }
    XCTAssertLessThan(Date().timeIntervalSince(start), 1)
  }
}
