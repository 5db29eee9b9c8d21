import Course
import Geometry
import SceneDescription
import XCTest

/// Week 4, transforms: an object placed by a matrix M
/// (`Transform.intersect`). The ray is taken into the object's space by
/// M⁻¹, its direction not normalised, so that t names the same point in
/// both spaces; the object's normal is brought back by the inverse
/// transpose (M⁻¹)ᵀ, which keeps it perpendicular to the moved surface,
/// and normalised. Tested on spheres, last week's shape.
final class Week4_TransformTests: XCTestCase {
  let down = Vector3<Double>(0, 0, -1)

  func placed(_ matrix: Matrix4<Double>) throws -> Transform {
    try XCTUnwrap(
      Transform(matrix: matrix, object: Sphere(center: .zero, radius: 1)))
  }

  func hit(
    _ object: Transform, from origin: Vector3<Double> = .zero,
    _ direction: Vector3<Double>, after tMin: Double = 0,
    before tMax: Double = .infinity
  ) -> Hit<Double>? {
    object.intersect(
      Ray(origin: origin, direction: direction), after: tMin, before: tMax)
  }

  /// The unit sphere scaled by 2 and moved to (0, 0, −10) is the sphere of
  /// radius 2 there: hit at t = 8 from the origin, the far side at 12, with
  /// normals ±z. M⁻¹ of these powers of two and integers is exact, and so
  /// is everything after it: t within 4 ε (a division or two), the normal
  /// within 4 ε (its normalisation).
  func testIntersect_MovedAndScaled_SameTInBothSpaces() throws {
    let sphere = try placed(
      .translation(Vector3(0, 0, -10)) * .uniformScale(2))
    let near = try XCTUnwrap(hit(sphere, down))
    assertRelative(near.t, 8, epsilons: 4, "exact numbers, a division, allow")
    assertClose(near.normal, Vector3(0, 0, 1), epsilons: 4, "normalising")
    let far = try XCTUnwrap(hit(sphere, down, after: 8))
    assertRelative(far.t, 12, epsilons: 4, "exact numbers, a division, allow")
    assertClose(far.normal, Vector3(0, 0, -1), epsilons: 4, "normalising")
    XCTAssertNil(hit(sphere, down, before: 8), "tMax is open, in world t")
    // A direction of length 2 in the world: half the t.
    let twice = try XCTUnwrap(hit(sphere, down * 2))
    assertRelative(twice.t, 4, epsilons: 4, "exact numbers, a division, allow")
  }

  /// Moved out of the ray's way, or behind the eye: no hit.
  func testIntersect_Misses() throws {
    let aside = try placed(.translation(Vector3(3, 0, -10)))
    XCTAssertNil(hit(aside, down))
    let behind = try placed(.translation(Vector3(0, 0, 10)))
    XCTAssertNil(hit(behind, down))
  }

  /// A unit sphere moved, turned and scaled uniformly is the sphere placed
  /// in the world: the same t and normal. t within 16 ε·t (M⁻¹'s
  /// roundings, about ε per product, a few per coordinate) plus what the
  /// quadratic's discriminant may lose in each of the two, any correct
  /// formula: 8 ε·|f|²/(r·cos θ), f from the centre to the eye, θ the
  /// angle of incidence (`Week2_SphereTests` explains the term). The
  /// normal is (P − centre)/r: a t off by δ moves P by δ, the normal by
  /// δ/r; within that for both, and 8 ε for the two normalisations.
  func testIntersect_SimilarityIsThePlacedSphere() throws {
    let matrix =
      Matrix4<Double>.translation(Vector3(1, 2, -10))
      * .rotationY(degrees: 30) * .uniformScale(2)
    let moved = try placed(matrix)
    let world = Sphere(center: Vector3(1, 2, -10), radius: 2)
    var generator = SplitMix64(seed: 42)
    var hits = 0
    for _ in 0..<500 {
      let direction = (Vector3<Double>(1, 2, -10)
        + randomUnit(&generator) * 1.9).normalized()
      let ray = Ray(origin: .zero, direction: direction)
      let a = moved.intersect(ray, after: 0, before: .infinity)
      let b = world.intersect(ray, after: 0, before: .infinity)
      guard let a, let b else {
        XCTAssertTrue(a == nil && b == nil)
        continue
      }
      hits += 1
      let cosine = abs(b.normal.dot(direction))
      let f = Vector3<Double>(1, 2, -10).length
      let bound =
        16 * .ulpOfOne * b.t + 16 * .ulpOfOne * f * f / (2 * cosine)
      XCTAssertEqual(a.t, b.t, accuracy: bound)
      XCTAssertLessThanOrEqual(
        (a.normal - b.normal).maxMagnitude, bound / 2 + 8 * .ulpOfOne)
    }
    XCTAssertGreaterThan(hits, 400)
  }

  /// A sphere scaled by (4, 1, 1) is an ellipsoid: seen along x it is hit
  /// at x = ±4, with normals ±x; seen from above at (2, 10, 0) its normal
  /// is the inverse transpose's (x/16, y, z) direction, not the sphere's
  /// nor M's (4x, y, z). In the object's space every number of the first
  /// ray is exact; the second's discriminant is 20² − 4·99.25 = 3 exactly,
  /// so t = 10 − √3/2 within a few roundings of numbers up to 20 (4 ε·10),
  /// and the normal within that over the radius 1 (the hit's y is 10 − t)
  /// and its normalisation's 4 ε: 44 ε.
  func testIntersect_NonUniformScale_InverseTransposeNormal() throws {
    let ellipsoid = try placed(.scale(Vector3(4, 1, 1)))
    let side = try XCTUnwrap(
      hit(ellipsoid, from: Vector3(10, 0, 0), Vector3(-1, 0, 0)))
    assertRelative(side.t, 6, epsilons: 4, "exact numbers, a division, allow")
    assertClose(side.normal, Vector3(1, 0, 0), epsilons: 4, "normalising")
    let top = try XCTUnwrap(
      hit(ellipsoid, from: Vector3(2, 10, 0), Vector3(0, -1, 0)))
    // On the ellipsoid x²/16 + y² = 1 at x = 2: y = √(3/4).
    let y = (0.75).squareRoot()
    XCTAssertEqual(top.t, 10 - y, accuracy: 4 * .ulpOfOne * 10)
    assertClose(
      top.normal, Vector3(2.0 / 16, y, 0).normalized(), epsilons: 44,
      "t's 4 ε·10 over the radius and a normalisation allow")
  }

  func testInit_SingularMatrixIsNil() {
    XCTAssertNil(
      Transform(
        matrix: .scale(Vector3(1, 0, 1)),
        object: Sphere(center: .zero, radius: 1)))
  }

  func testBoundingBox_MovedWithTheObject() throws {
    let moved = try placed(.translation(Vector3(5, 0, 0)))
    XCTAssertEqual(moved.boundingBox?.lower, Vector3(4, -1, -1))
    XCTAssertEqual(moved.boundingBox?.upper, Vector3(6, 1, 1))
  }
}
