import Geometry
import SceneDescription
import XCTest

@testable import FastEngine
@testable import FastKernels

/// `Group.primitiveCounts`, which a course-engine render reports without
/// flattening the scene, counts what flattening makes.
final class PrimitiveCountsTests: XCTestCase {
  func testCounts_AsFlattened() throws {
    let sphere = SceneObject<Double>.sphere(
      SceneDescription.Sphere(center: .zero, radius: 1))
    let triangle = SceneDescription.Triangle<Double>(
      Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0))
    let stretched = try XCTUnwrap(
      SceneDescription.Transform(
        matrix: .scale(Vector3(1, 2, 3)), object: sphere))
    let turned = try XCTUnwrap(
      SceneDescription.Transform(
        matrix: .rotationY(degrees: 30) * .uniformScale(2),
        object: .group(
          SceneDescription.Group([
            sphere, .triangle(triangle), .transform(stretched),
          ]))))
    let group = SceneDescription.Group<Double>([
      sphere,
      .plane(SceneDescription.Plane(normal: Vector3(0, 1, 0), offset: 0)),
      .mesh(SceneDescription.TriangleMesh([triangle, triangle])),
      .transform(stretched), .transform(turned),
    ])
    let counts = group.primitiveCounts
    let all = group.flattened()
    XCTAssertEqual(counts.spheres, all.spheres.count)
    XCTAssertEqual(counts.planes, all.planes.count)
    XCTAssertEqual(counts.triangles, all.triangles.count)
    XCTAssertEqual(counts.ellipsoids, all.transformedSpheres.count)
    XCTAssertEqual(
      [counts.spheres, counts.planes, counts.triangles, counts.ellipsoids],
      [2, 1, 3, 2])
  }
}
