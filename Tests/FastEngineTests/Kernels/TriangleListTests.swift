import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// A flattened scene's triangles, loose and meshes, in file order
/// (`TriangleList`).
final class TriangleListTests: XCTestCase {
  func triangle(_ x: Double, z: Double = -5, material: Int) -> Triangle<
    Double
  > {
    Triangle(
      Vector3(x - 1, -1, z), Vector3(x + 1, -1, z), Vector3(x, 1, z),
      materialIndex: material)
  }

  /// Loose triangles between meshes are gathered into parts of their own;
  /// the triangles come out in the order they went in, by iteration and by
  /// position alike.
  func testOrder_LooseAndMeshes() {
    let first = TriangleMesh((0..<3).map { triangle(Double($0), material: 1) })
    let second = TriangleMesh((0..<2).map { triangle(Double($0), material: 2) })
    let loose = (0..<4).map { triangle(Double($0), z: -4, material: 3) }
    var list = TriangleList<Double>()
    list.append(loose[0])
    list.append(first)
    list.append(loose[1])
    list.append(loose[2])
    list.append(TriangleMesh())
    list.append(second)
    list.append(first)
    list.append(loose[3])
    let want =
      [loose[0]] + Array(first) + [loose[1], loose[2]] + Array(second)
      + Array(first) + [loose[3]]
    XCTAssertEqual(list.count, want.count)
    XCTAssertEqual(Array(list), want)
    for index in want.indices.reversed() {
      XCTAssertEqual(list[index], want[index], "position \(index)")
    }
    XCTAssertEqual(list.parts.count, 6)
    // Equal to the same triangles however they are held.
    XCTAssertEqual(list, TriangleList(want))
    XCTAssertNotEqual(list, TriangleList(want.dropLast()))
    XCTAssertNotEqual(list, TriangleList(want.reversed()))
    XCTAssertTrue(TriangleList<Double>().isEmpty)
  }

  /// Coincident triangles: the first in file order wins the tie, whether
  /// loose or in a mesh, in the model and in the compiled scene alike.
  func testTies_GoToTheEarlierTriangle() throws {
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: .zero, direction: Vector3(0, 0, -1), up: Vector3(0, 1, 0),
        angle: 30))
    let ray = Ray<Double>(origin: .zero, direction: Vector3(0, 0, -1))
    let orders: [(Group<Double>, Int)] = [
      (
        Group([
          .triangle(triangle(0, material: 1)),
          .mesh(TriangleMesh([triangle(0, material: 2)])),
        ]), 1
      ),
      (
        Group([
          .mesh(TriangleMesh([triangle(0, material: 2)])),
          .triangle(triangle(0, material: 1)),
        ]), 2
      ),
      (
        Group([
          .mesh(TriangleMesh([triangle(3, material: 4)])),
          .mesh(TriangleMesh([triangle(0, material: 2)])),
          .group(Group([.mesh(TriangleMesh([triangle(0, material: 3)]))])),
        ]), 2
      ),
    ]
    for (root, want) in orders {
      let all = root.flattened()
      for method in IntersectionMethod.allCases {
        XCTAssertEqual(
          root.intersect(ray, after: 0, before: .infinity, method: method)?
            .materialIndex, want)
        XCTAssertEqual(
          all.intersect(ray, after: 0, before: .infinity, method: method)?
            .materialIndex, want)
      }
      let compiled = CompiledScene<StableKernel<Double>>(
        Scene(camera: camera, root: root))
      let hit = try XCTUnwrap(
        compiled.nearest(
          CameraRay(origin: compiled.rayOrigin, direction: Vector3(0, 0, -1))))
      XCTAssertEqual(compiled.materialIndex(of: hit.what), want)
    }
  }
}
