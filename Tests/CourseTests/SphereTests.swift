import Course
import Geometry
import SceneDescription
import XCTest


/// The course's sphere: the quadratic's cases (outside, inside, tangent,
/// miss, behind, the interval) and its normal, each checked against t and
/// normals known exactly.
final class SphereTests: XCTestCase {
  /// A sphere of radius 2 ten units down −z from the origin.
  let sphere = Sphere(center: Vector3(0, 0, -10), radius: 2, materialIndex: 3)
  let down = Vector3<Double>(0, 0, -1)

  func hit(
    _ origin: Vector3<Double>, _ direction: Vector3<Double>,
    after tMin: Double = 0, before tMax: Double = .infinity
  ) -> Hit<Double>? {
    sphere.intersect(
      Ray(origin: origin, direction: direction), after: tMin, before: tMax)
  }

  func testIntersect_FromOutside_NearSide() throws {
    let found = try XCTUnwrap(hit(.zero, down))
    XCTAssertEqual(found.t, 8)
    XCTAssertEqual(found.normal, Vector3(0, 0, 1))
    XCTAssertEqual(found.materialIndex, 3)
  }

  func testIntersect_FromInside_FarSide() throws {
    let found = try XCTUnwrap(hit(Vector3(0, 0, -10), down))
    XCTAssertEqual(found.t, 2)
    XCTAssertEqual(found.normal, Vector3(0, 0, -1), "outward, along the ray")
  }

  func testIntersect_Tangent_DoubleRoot() throws {
    let found = try XCTUnwrap(hit(Vector3(0, 2, 0), down))
    XCTAssertEqual(found.t, 10)
    XCTAssertEqual(found.normal, Vector3(0, 1, 0))
  }

  func testIntersect_Miss() {
    XCTAssertNil(hit(Vector3(0, 2.0001, 0), down))
    XCTAssertNil(hit(.zero, Vector3(0, 1, 0)))
  }

  func testIntersect_SphereBehind() {
    XCTAssertNil(hit(.zero, Vector3(0, 0, 1)))
  }

  func testIntersect_Interval() throws {
    XCTAssertNil(hit(.zero, down, before: 8), "tMax is open")
    XCTAssertNil(hit(.zero, down, after: 12), "both roots before tMin")
    let far = try XCTUnwrap(hit(.zero, down, after: 8))
    XCTAssertEqual(far.t, 12, "the far root when the near one is not after")
    XCTAssertEqual(far.normal, Vector3(0, 0, -1))
  }

  /// t is in multiples of the direction: twice as long, half the t.
  func testIntersect_NonUnitDirection() throws {
    let found = try XCTUnwrap(hit(.zero, down * 2))
    XCTAssertEqual(found.t, 4)
    XCTAssertEqual(found.normal, Vector3(0, 0, 1))
  }

  /// Rays aimed at known points of random spheres: the hit is that point,
  /// and its normal is unit length (within 4 ε) and points out of the
  /// sphere. t is held to what the case's conditioning allows any correct
  /// formula, the slide's included:
  /// - 64 ε of the lengths involved over the cosine of the angle of
  ///   incidence: the aimed point and the origin are each rounded, by about
  ///   ε times the coordinates, and a rounding across the surface moves t
  ///   by that over the cosine;
  /// - plus 8 ε·|f|²/(r·cos θ), f = o − centre: the discriminant b² − 4ac
  ///   is a difference of terms of size |f|², each rounded, and its square
  ///   root r·cos θ moves by that over twice itself. The stable form does
  ///   not lose this (`SphereTests_Stability` holds it to that); the
  ///   slide's b² − 4ac does, within this bound.
  func testIntersect_RandomRaysHitTheirPoints() throws {
    var generator = SplitMix64(seed: 0x5EED_5FE4)
    for iteration in 0..<2000 {
      let center = Vector3<Double>(
        .random(in: -50...50, using: &generator),
        .random(in: -50...50, using: &generator),
        .random(in: -50...50, using: &generator))
      let radius = Double.random(in: 0.1...10, using: &generator)
      let outward = randomUnit(&generator)
      var direction = randomUnit(&generator)
      if direction.dot(outward) > 0 { direction = -direction }
      let expected = Double.random(in: 1...(100 * radius), using: &generator)
      let point = center + outward * radius
      let origin = point - direction * expected
      let cosine = -direction.dot(outward)
      // Rays within 0.06° of the tangent may miss by a rounding: skipped.
      guard cosine > 1e-3 else { continue }
      let found = Sphere(center: center, radius: radius).intersect(
        Ray(origin: origin, direction: direction), after: 0, before: .infinity)
      let f = (origin - center).length
      let bound =
        64 * Double.ulpOfOne * (expected + radius + center.length) / cosine
        + 8 * Double.ulpOfOne * f * f / (radius * cosine)
      guard let found, (found.t - expected).magnitude <= bound,
        (found.normal.length - 1).magnitude <= 4 * .ulpOfOne,
        found.normal.dot(outward) > 0.999
      else {
        // One message for the first ray that fails, not one per ray.
        return XCTFail(
          "iteration \(iteration): expected t = \(expected) (± \(bound)) "
            + "and normal \(outward), found \(String(describing: found))")
      }
    }
  }

  func testBoundingBox() {
    XCTAssertEqual(sphere.boundingBox?.lower, Vector3(-2, -2, -12))
    XCTAssertEqual(sphere.boundingBox?.upper, Vector3(2, 2, -8))
  }
}

func randomUnit(_ generator: inout SplitMix64) -> Vector3<Double> {
  while true {
    let v = Vector3<Double>(
      .random(in: -1...1, using: &generator),
      .random(in: -1...1, using: &generator),
      .random(in: -1...1, using: &generator))
    let squared = v.lengthSquared
    if squared > 1e-4 && squared <= 1 { return v / squared.squareRoot() }
  }
}
