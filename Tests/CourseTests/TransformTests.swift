import Course
import Geometry
import SceneDescription
import XCTest


/// The course's transform: the ray taken into the object's space by M⁻¹,
/// the normal brought back by the inverse transpose.
final class TransformTests: XCTestCase {
  /// A unit sphere moved and scaled uniformly is the sphere placed in the
  /// world: the same t and normal, within 16 ε·t (M⁻¹'s roundings) and
  /// what the quadratic's discriminant may lose in each of the two, any
  /// correct formula: 8 ε·|f|²/(r·cos θ), f from the centre to the eye,
  /// θ the angle of incidence (`SphereTests` explains the term).
  func testIntersect_SimilarityIsThePlacedSphere() throws {
    let matrix =
      Matrix4<Double>.translation(Vector3(1, 2, -10))
      * .rotationY(degrees: 30) * .uniformScale(2)
    let moved = try XCTUnwrap(
      Transform(matrix: matrix, object: Sphere(center: .zero, radius: 1)))
    let placed = Sphere(center: Vector3(1, 2, -10), radius: 2)
    var generator = SplitMix64(seed: 42)
    var hits = 0
    for _ in 0..<500 {
      let direction = (Vector3<Double>(1, 2, -10)
        + randomUnit(&generator) * 1.9).normalized()
      let ray = Ray(origin: .zero, direction: direction)
      let a = moved.intersect(ray, after: 0, before: .infinity)
      let b = placed.intersect(ray, after: 0, before: .infinity)
      guard let a, let b else {
        XCTAssertTrue(a == nil && b == nil)
        continue
      }
      hits += 1
      let cosine = abs(b.normal.dot(direction))
      let f = Vector3<Double>(1, 2, -10).length
      XCTAssertEqual(
        a.t, b.t,
        accuracy: 16 * .ulpOfOne * b.t + 16 * .ulpOfOne * f * f / (2 * cosine))
      XCTAssertEqual((a.normal - b.normal).length, 0, accuracy: 1e-12)
    }
    XCTAssertGreaterThan(hits, 400)
  }

  /// A sphere scaled by (4, 1, 1) is an ellipsoid: seen along x it is hit
  /// at x = ±4, with normals ±x; seen from above at (2, 10, 0) its normal
  /// is the inverse transpose's (x/16, y, z) direction, not the sphere's.
  func testIntersect_NonUniformScale_InverseTransposeNormal() throws {
    let ellipsoid = try XCTUnwrap(
      Transform(
        matrix: .scale(Vector3(4, 1, 1)),
        object: Sphere(center: .zero, radius: 1)))
    let side = try XCTUnwrap(
      ellipsoid.intersect(
        Ray(origin: Vector3(10, 0, 0), direction: Vector3(-1, 0, 0)),
        after: 0, before: .infinity))
    XCTAssertEqual(side.t, 6, accuracy: 8 * .ulpOfOne)
    XCTAssertEqual(side.normal, Vector3(1, 0, 0))
    let top = try XCTUnwrap(
      ellipsoid.intersect(
        Ray(origin: Vector3(2, 10, 0), direction: Vector3(0, -1, 0)),
        after: 0, before: .infinity))
    // On the ellipsoid x²/16 + y² = 1 at x = 2: y = √(3/4).
    let y = (0.75).squareRoot()
    XCTAssertEqual(top.t, 10 - y, accuracy: 16 * .ulpOfOne * 10)
    let expected = Vector3(2.0 / 16, y, 0).normalized()
    XCTAssertEqual((top.normal - expected).length, 0, accuracy: 1e-14)
  }

  func testInit_SingularMatrixIsNil() {
    XCTAssertNil(
      Transform(
        matrix: .scale(Vector3(1, 0, 1)),
        object: Sphere(center: .zero, radius: 1)))
  }

  func testBoundingBox_MovedWithTheObject() throws {
    let moved = try XCTUnwrap(
      Transform(
        matrix: .translation(Vector3(5, 0, 0)),
        object: Sphere(center: .zero, radius: 1)))
    XCTAssertEqual(moved.boundingBox?.lower, Vector3(4, -1, -1))
    XCTAssertEqual(moved.boundingBox?.upper, Vector3(6, 1, 1))
  }
}
