import Course
import Geometry
import SceneDescription
import XCTest

/// Week 1, camera and planes: the plane n·P = d (`Plane.intersect`).
/// t = (d − n·o)/(n·d); a hit when t is in (tMin, tMax); the normal is the
/// plane's own, whichever side the ray comes from.
final class Week1_PlaneTests: XCTestCase {
  /// The floor y = −1.
  let floor = Plane(normal: Vector3(0, 1, 0), offset: -1, materialIndex: 2)

  func hit(
    _ origin: Vector3<Double>, _ direction: Vector3<Double>,
    after tMin: Double = 0, before tMax: Double = .infinity
  ) -> Hit<Double>? {
    floor.intersect(
      Ray(origin: origin, direction: direction), after: tMin, before: tMax)
  }

  /// Small integers, one division: any correct formula gives t to within
  /// a rounding (2 ε).
  static let exact = "a division of small integers allows"

  func testIntersect_FromAbove() throws {
    let found = try XCTUnwrap(hit(Vector3(0, 3, 0), Vector3(0, -1, 0)))
    assertRelative(found.t, 4, epsilons: 2, Self.exact)
    XCTAssertEqual(found.normal, Vector3(0, 1, 0), "the plane's own")
    XCTAssertEqual(found.materialIndex, 2)
  }

  func testIntersect_FromBelow_KeepsItsNormal() throws {
    let found = try XCTUnwrap(hit(Vector3(0, -5, 0), Vector3(0, 1, 0)))
    assertRelative(found.t, 4, epsilons: 2, Self.exact)
    XCTAssertEqual(found.normal, Vector3(0, 1, 0), "not turned to the ray")
  }

  /// t is in multiples of the direction: twice as long, half the t; an
  /// oblique (3, −4, 0) from (0, 3, 0) meets y = −1 at t = 1, at (3, −1, 0).
  func testIntersect_NonUnitDirection() throws {
    let twice = try XCTUnwrap(hit(Vector3(0, 3, 0), Vector3(0, -2, 0)))
    assertRelative(twice.t, 2, epsilons: 2, Self.exact)
    let oblique = try XCTUnwrap(hit(Vector3(0, 3, 0), Vector3(3, -4, 0)))
    assertRelative(oblique.t, 1, epsilons: 2, Self.exact)
    XCTAssertEqual(oblique.normal, Vector3(0, 1, 0))
  }

  /// A ray parallel to the plane never meets it (n·d = 0: t is infinite,
  /// or undefined for a ray in the plane).
  func testIntersect_Parallel_Misses() {
    XCTAssertNil(hit(Vector3(0, 3, 0), Vector3(1, 0, 0)), "above it")
    XCTAssertNil(hit(Vector3(0, -1, 0), Vector3(1, 0, 0)), "in it")
  }

  /// A ray going away from the plane meets it at t < 0: behind the eye.
  func testIntersect_PlaneBehind_Misses() {
    XCTAssertNil(hit(Vector3(0, 3, 0), Vector3(0, 1, 0)))
    XCTAssertNil(hit(Vector3(0, -5, 0), Vector3(0, -1, 0)))
  }

  /// The interval (tMin, tMax) is open at both ends.
  func testIntersect_Interval() {
    let above = Vector3<Double>(0, 3, 0)
    let down = Vector3<Double>(0, -1, 0)
    XCTAssertNil(hit(above, down, before: 4), "t = tMax")
    XCTAssertNil(hit(above, down, after: 4), "t = tMin")
    XCTAssertNil(hit(above, down, before: 3), "beyond tMax")
    XCTAssertNotNil(hit(above, down, after: 3.5, before: 4.5))
  }

  /// A tilted plane through the origin, n = (1, 1, 0)/√2, hit from (1, 1, 0)
  /// along −x: t = 2. n·o and n·d are sums of products of the same sign
  /// (no cancellation), so t is within a few roundings of them: 4 ε.
  func testIntersect_Tilted() throws {
    let normal = Vector3<Double>(1, 1, 0).normalized()
    let plane = Plane(normal: normal, offset: 0)
    let found = try XCTUnwrap(
      plane.intersect(
        Ray(origin: Vector3(1, 1, 0), direction: Vector3(-1, 0, 0)),
        after: 0, before: .infinity))
    assertRelative(found.t, 2, epsilons: 4, "two dot products and a division")
    XCTAssertEqual(found.normal, normal)
  }

  /// Random planes, random rays (not of unit length) aimed at a point of
  /// each: every ray hits, and its point o + t·d is on the plane as far as
  /// the numbers allow. That is the residual n·(o + t·d) − d, within
  /// 8 ε·(|d| + Σ|nᵢoᵢ| + t·Σ|nᵢdᵢ|): each of n·o, n·d and this test's own
  /// n·(o + t·d) is a sum of three products, each rounded, and t's
  /// relative error from them is bounded by the same terms, whatever the
  /// angle (the residual needs no conditioning factor).
  func testIntersect_RandomRaysReachThePlane() throws {
    var generator = SplitMix64(seed: 0x91A9_E5)
    var hits = 0
    for iteration in 0..<2000 {
      let normal = randomUnit(&generator)
      let point = Vector3<Double>(
        .random(in: -100...100, using: &generator),
        .random(in: -100...100, using: &generator),
        .random(in: -100...100, using: &generator))
      let offset = normal.dot(point)
      let direction =
        randomUnit(&generator) * .random(in: 0.5...2, using: &generator)
      // Within about 0.5° of the plane, t is too large to aim: skipped.
      guard (normal.dot(direction) / direction.length).magnitude > 0.01
      else { continue }
      let origin =
        point - direction * .random(in: 1...100, using: &generator)
      let plane = Plane(normal: normal, offset: offset)
      let found = try XCTUnwrap(
        plane.intersect(
          Ray(origin: origin, direction: direction), after: 0,
          before: .infinity), "iteration \(iteration): missed")
      let t = found.t
      let residual = normal.dot(origin + direction * t) - offset
      let scale =
        offset.magnitude + (normal * origin).magnitudeSum
        + t * (normal * direction).magnitudeSum
      guard residual.magnitude <= 8 * .ulpOfOne * scale,
        found.normal == normal
      else {
        return XCTFail(
          "iteration \(iteration): n·(o + t·d) − d = \(residual), more than "
            + "8 ε·\(scale); normal \(found.normal), not \(normal)")
      }
      hits += 1
    }
    XCTAssertGreaterThan(hits, 1900)
  }
}
