import Course
import Geometry
import SceneDescription
import XCTest


/// The course's triangle: inside and outside by the barycentric
/// coordinates of Cramer's rule, t, the winding's normal, interpolated
/// normals and texture coordinates.
final class TriangleTests: XCTestCase {
  /// In the plane z = −5, counter-clockwise seen from the origin.
  let triangle = Triangle(
    Vector3(-1, -1, -5), Vector3(1, -1, -5), Vector3(0, 1, -5),
    materialIndex: 1)

  func ray(towards x: Double, _ y: Double) -> Ray<Double> {
    Ray(origin: Vector3(x, y, 0), direction: Vector3(0, 0, -1))
  }

  func testIntersect_Inside() throws {
    let found = try XCTUnwrap(
      triangle.intersect(ray(towards: 0, 0), after: 0, before: .infinity))
    XCTAssertEqual(found.t, 5)
    XCTAssertEqual(found.normal, Vector3(0, 0, 1), "the winding's normal")
    XCTAssertEqual(found.materialIndex, 1)
  }

  func testIntersect_Outside() {
    for (x, y) in [(0.0, 1.01), (-1.01, -1.0), (0.6, 0.0), (0.0, -1.01)] {
      XCTAssertNil(
        triangle.intersect(ray(towards: x, y), after: 0, before: .infinity),
        "(\(x), \(y))")
    }
  }

  func testIntersect_BackFace_KeepsTheWindingsNormal() throws {
    let back = Ray(origin: Vector3(0, 0, -10), direction: Vector3(0, 0, 1))
    let found = try XCTUnwrap(
      triangle.intersect(back, after: 0, before: .infinity))
    XCTAssertEqual(found.t, 5)
    XCTAssertEqual(found.normal, Vector3(0, 0, 1))
  }

  func testIntersect_Interval() {
    XCTAssertNil(triangle.intersect(ray(towards: 0, 0), after: 0, before: 5))
    XCTAssertNil(
      triangle.intersect(ray(towards: 0, 0), after: 5, before: .infinity))
  }

  /// Vertex normals are interpolated by the barycentric weights, then
  /// normalised; so are texture coordinates.
  func testIntersect_InterpolatesNormalsAndTextureCoordinates() throws {
    var smooth = triangle
    smooth.normals = (Vector3(1, 0, 0), Vector3(0, 2, 0), Vector3(0, 0, 3))
    smooth.textureCoordinates = (
      TextureCoordinate(0, 0), TextureCoordinate(1, 0),
      TextureCoordinate(0.5, 1)
    )
    // (0.5, −1) is the midpoint of the first edge: weights ½, ½, 0.
    let found = try XCTUnwrap(
      smooth.intersect(ray(towards: 0.5 - 0.5, -1 + 1e-9), after: 0,
        before: .infinity))
    let expected = Vector3<Double>(0.5, 1, 0).normalized()
    XCTAssertEqual(found.normal.x, expected.x, accuracy: 1e-8)
    XCTAssertEqual(found.normal.y, expected.y, accuracy: 1e-8)
    XCTAssertEqual(found.normal.z, expected.z, accuracy: 1e-8)
    XCTAssertEqual(found.textureCoordinate?.u ?? -1, 0.5, accuracy: 1e-8)
    XCTAssertEqual(found.textureCoordinate?.v ?? -1, 0, accuracy: 1e-8)
  }

  /// Random rays through random points of random triangles: each hits at
  /// its point (t within 64 ε relative) when the point is well inside.
  func testIntersect_RandomRaysHitTheirPoints() throws {
    var generator = SplitMix64(seed: 0x7A1A_9913)
    func point() -> Vector3<Double> {
      Vector3(
        .random(in: -10...10, using: &generator),
        .random(in: -10...10, using: &generator),
        .random(in: -10...10, using: &generator))
    }
    var hits = 0
    for iteration in 0..<2000 {
      let (a, b, c) = (point(), point(), point())
      let beta = Double.random(in: 0.05...0.45, using: &generator)
      let gamma = Double.random(in: 0.05...0.45, using: &generator)
      let target = a + (b - a) * beta + (c - a) * gamma
      let direction = randomUnit(&generator)
      let expected = Double.random(in: 1...50, using: &generator)
      let origin = target - direction * expected
      let normal = (b - a).cross(c - a).normalized()
      // Rays within ~1° of the plane are ill-conditioned: skipped.
      guard abs(normal.dot(direction)) > 0.02 else { continue }
      let found = try XCTUnwrap(
        Triangle(a, b, c).intersect(
          Ray(origin: origin, direction: direction), after: 0,
          before: .infinity), "iteration \(iteration)")
      XCTAssertEqual(
        found.t, expected, accuracy: 64 * .ulpOfOne * (expected + 20) / abs(normal.dot(direction)),
        "iteration \(iteration)")
      hits += 1
    }
    XCTAssertGreaterThan(hits, 1500)
  }
}
