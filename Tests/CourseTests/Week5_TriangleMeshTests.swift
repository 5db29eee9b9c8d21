import Course
import Geometry
import SceneDescription
import XCTest

/// Week 5, triangles and meshes: the mesh (`TriangleMesh.intersect`), the
/// nearest hit of its triangles, which its hierarchy of boxes hands over
/// (given) so that a ray tests only those whose boxes it meets.
final class Week5_TriangleMeshTests: XCTestCase {
  /// A triangle in the plane z = −depth around the −z axis.
  func facing(_ depth: Double, material: Int) -> Triangle {
    Triangle(
      Vector3(-1, -1, -depth), Vector3(1, -1, -depth), Vector3(0, 1, -depth),
      materialIndex: material)
  }

  let down = Ray<Double>(origin: .zero, direction: Vector3(0, 0, -1))

  /// Three triangles one behind the other, in any order: the nearest, in
  /// (tMin, tMax).
  func testIntersect_TheNearest() throws {
    for order in [[5.0, 3, 4], [3, 4, 5], [4, 5, 3]] {
      let mesh = TriangleMesh(order.map { facing($0, material: Int($0)) })
      let found = try XCTUnwrap(
        mesh.intersect(down, after: 0, before: .infinity), "\(order)")
      XCTAssertEqual(found.materialIndex, 3, "\(order)")
      let after = try XCTUnwrap(
        mesh.intersect(down, after: 3, before: .infinity), "\(order)")
      XCTAssertEqual(after.materialIndex, 4, "\(order): after tMin")
      XCTAssertNil(mesh.intersect(down, after: 0, before: 3), "\(order)")
    }
  }

  func testIntersect_Misses() {
    let mesh = TriangleMesh([facing(3, material: 0), facing(5, material: 1)])
    XCTAssertNil(
      mesh.intersect(
        Ray(origin: Vector3(0, 2, 0), direction: Vector3(0, 0, -1)),
        after: 0, before: .infinity), "beside")
    XCTAssertNil(
      mesh.intersect(
        Ray(origin: .zero, direction: Vector3(0, 0, 1)), after: 0,
        before: .infinity), "behind")
  }

  /// 600 random triangles: the mesh finds the same nearest hit as a group
  /// of the same triangles, each asked in turn (the same triangle's own
  /// intersection, so the same t exactly).
  func testIntersect_HierarchyFindsTheNearestOfAll() {
    var generator = SplitMix64(seed: 7)
    func point() -> Vector3<Double> {
      Vector3(
        .random(in: -5...5, using: &generator),
        .random(in: -5...5, using: &generator),
        .random(in: -5...5, using: &generator))
    }
    var triangles: [Triangle] = []
    for index in 0..<600 {
      let corner = point()
      triangles.append(
        Triangle(
          corner, corner + randomUnit(&generator),
          corner + randomUnit(&generator), materialIndex: index))
    }
    let mesh = TriangleMesh(triangles)
    let everyOne = Group(triangles)
    var hits = 0
    for _ in 0..<3000 {
      // From a sphere of radius 20 towards a corner of a random triangle,
      // a little off it.
      let origin = randomUnit(&generator) * 20
      let aim = triangles[Int.random(in: 0..<600, using: &generator)].a
        + randomUnit(&generator) * 0.3
      let ray = Ray(origin: origin, direction: aim - origin)
      let a = mesh.intersect(ray, after: 0, before: .infinity)
      let b = everyOne.intersect(ray, after: 0, before: .infinity)
      XCTAssertEqual(a?.t, b?.t)
      if a != nil { hits += 1 }
    }
    XCTAssertGreaterThan(hits, 300)
  }

  func testEmptyMesh_NeverHit() {
    let mesh = TriangleMesh([])
    XCTAssertNil(mesh.intersect(down, after: 0, before: .infinity))
    XCTAssertNil(mesh.boundingBox)
  }
}
