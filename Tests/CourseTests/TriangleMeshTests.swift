import Course
import Geometry
import SceneDescription
import XCTest


/// The course's mesh: its hierarchy finds the same nearest hit as testing
/// every triangle.
final class TriangleMeshTests: XCTestCase {
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
    XCTAssertNil(
      mesh.intersect(
        Ray(origin: .zero, direction: Vector3(0, 0, -1)), after: 0,
        before: .infinity))
    XCTAssertNil(mesh.boundingBox)
  }
}
