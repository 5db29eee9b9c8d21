import Course
import Geometry
import SceneDescription
import XCTest

/// Week 5, triangles and meshes: the triangle (`Triangle.intersect`). The
/// ray's point o + t·d is the triangle's a + β(b − a) + γ(c − a) when
/// β(b − a) + γ(c − a) − t·d = o − a: three equations in β, γ and t, by
/// Cramer's rule. A hit when β ≥ 0, γ ≥ 0, β + γ ≤ 1 and t is in
/// (tMin, tMax); the normal is the winding's, (b − a) × (c − a), or the
/// vertex normals interpolated by (1 − β − γ, β, γ), normalised.
final class Week5_TriangleTests: XCTestCase {
  /// In the plane z = −5, counter-clockwise seen from the origin.
  let triangle = Triangle(
    Vector3(-1, -1, -5), Vector3(1, -1, -5), Vector3(0, 1, -5),
    materialIndex: 1)
  let down = Vector3<Double>(0, 0, -1)

  func ray(towards x: Double, _ y: Double) -> Ray<Double> {
    Ray(origin: Vector3(x, y, 0), direction: Vector3(0, 0, -1))
  }

  /// The cases' determinants are products of small binary fractions,
  /// exact: t within a division or two (4 ε), the normal within its
  /// normalisation (4 ε).
  static let exact = "exact determinants and a division or two allow"
  static let unit = "normalising a vector allows"

  func testIntersect_Inside() throws {
    let found = try XCTUnwrap(
      triangle.intersect(ray(towards: 0, 0), after: 0, before: .infinity))
    assertRelative(found.t, 5, epsilons: 4, Self.exact)
    assertClose(found.normal, Vector3(0, 0, 1), epsilons: 4, Self.unit)
    XCTAssertEqual(found.materialIndex, 1)
  }

  /// Just outside each edge (β < 0, γ < 0, β + γ > 1) and beyond each
  /// corner.
  func testIntersect_Outside() {
    let outside = [
      (0.0, -1.01), (0.55, 0.0), (-0.55, 0.0),
      (-1.01, -1.0), (1.01, -1.0), (0.0, 1.01),
    ]
    for (x, y) in outside {
      XCTAssertNil(
        triangle.intersect(ray(towards: x, y), after: 0, before: .infinity),
        "(\(x), \(y))")
    }
  }

  /// From behind, the same t and the winding's normal, not turned to the
  /// ray.
  func testIntersect_BackFace_KeepsTheWindingsNormal() throws {
    let back = Ray(origin: Vector3(0, 0, -10), direction: Vector3(0, 0, 1))
    let found = try XCTUnwrap(
      triangle.intersect(back, after: 0, before: .infinity))
    assertRelative(found.t, 5, epsilons: 4, Self.exact)
    assertClose(found.normal, Vector3(0, 0, 1), epsilons: 4, Self.unit)
  }

  /// Behind the eye (t < 0), or parallel to its plane: no hit.
  func testIntersect_BehindOrParallel_Misses() {
    XCTAssertNil(
      triangle.intersect(
        Ray(origin: .zero, direction: Vector3(0, 0, 1)), after: 0,
        before: .infinity), "behind")
    XCTAssertNil(
      triangle.intersect(
        Ray(origin: Vector3(-5, 0, -4), direction: Vector3(1, 0, 0)),
        after: 0, before: .infinity), "parallel")
  }

  /// t is in multiples of the direction: twice as long, half the t.
  func testIntersect_NonUnitDirection() throws {
    let found = try XCTUnwrap(
      triangle.intersect(
        Ray(origin: .zero, direction: down * 2), after: 0, before: .infinity))
    assertRelative(found.t, 2.5, epsilons: 4, Self.exact)
  }

  /// The interval (tMin, tMax) is open at both ends.
  func testIntersect_Interval() {
    XCTAssertNil(triangle.intersect(ray(towards: 0, 0), after: 0, before: 5))
    XCTAssertNil(
      triangle.intersect(ray(towards: 0, 0), after: 5, before: .infinity))
  }

  /// Vertex normals are interpolated by the barycentric weights, then
  /// normalised; so are texture coordinates. At (−0.25, −0.5) the weights
  /// are (½, ¼, ¼), binary fractions: the normal ½(1, 0, 0) + ¼(0, 2, 0) +
  /// ¼(0, 0, 3) = (0.5, 0.5, 0.75) within its normalisation (4 ε), the
  /// coordinates (0.375, 0.25) within a rounding or two (4 ε).
  func testIntersect_InterpolatesNormalsAndTextureCoordinates() throws {
    var smooth = triangle
    smooth.normals = (Vector3(1, 0, 0), Vector3(0, 2, 0), Vector3(0, 0, 3))
    smooth.textureCoordinates = (
      TextureCoordinate(0, 0), TextureCoordinate(1, 0),
      TextureCoordinate(0.5, 1)
    )
    let found = try XCTUnwrap(
      smooth.intersect(
        ray(towards: -0.25, -0.5), after: 0, before: .infinity))
    assertClose(
      found.normal, Vector3(0.5, 0.5, 0.75).normalized(), epsilons: 4,
      Self.unit)
    let coordinate = try XCTUnwrap(found.textureCoordinate)
    assertRelative(coordinate.u, 0.375, epsilons: 4, Self.exact)
    assertRelative(coordinate.v, 0.25, epsilons: 4, Self.exact)
  }

  /// Random rays through random points of random triangles: each hits at
  /// its point when the point is well inside (β, γ ≥ 0.05). t within
  /// 64 ε·(t + 20)/|cos θ|, θ the angle of incidence: the corners, the aimed
  /// point and the origin are rounded by about ε times their coordinates
  /// (up to 10, and t + 10 for the origin), and so is each product of the
  /// determinants; a rounding across the plane moves t by that over the
  /// cosine.
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
      let cosine = normal.dot(direction).magnitude
      // Rays within ~1° of the plane are ill-conditioned: skipped.
      guard cosine > 0.02 else { continue }
      let found = try XCTUnwrap(
        Triangle(a, b, c).intersect(
          Ray(origin: origin, direction: direction), after: 0,
          before: .infinity), "iteration \(iteration)")
      XCTAssertEqual(
        found.t, expected,
        accuracy: 64 * .ulpOfOne * (expected + 20) / cosine,
        "iteration \(iteration)")
      hits += 1
    }
    XCTAssertGreaterThan(hits, 1500)
  }
}
