import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The watertight test's own t against the exact one, over random
/// triangles sorted by `TrianglePlane.needsExactT`'s error factor: below
/// its limit of 16 (where the fast engine keeps the watertight t) the
/// error stays within 5/cos θ ulps (measured 4.2), no more than for an
/// equilateral triangle; above it the error grows with the factor, which
/// is why those triangles take t from their exact planes.
final class WatertightErrorTests: XCTestCase {
  func check<S: RayScalar>(_: S.Type) {
    var generator = SplitMix64(seed: 3)
    func uniform() -> Double {
      Double(generator.next() % 1_000_000_007) / 1_000_000_007
    }
    func direction() -> Vector3<Double> {
      Vector3(uniform() * 2 - 1, uniform() * 2 - 1, uniform() * 2 - 1)
        .normalized()
    }
    var kept = 0.0  // worst ulps·cos θ where the watertight t is kept
    var replaced = 0.0  // the same where the exact plane replaces it
    var count = 0
    let triangles = Self.seedCount(3000)
    for _ in 0..<triangles {
      let distance = pow(10, uniform() * 2 - 0.5)
      let size = distance * pow(10, uniform() * 3 - 2)
      let aspect = pow(10, -uniform() * 3)
      let centre = direction() * distance
      let axis = direction()
      let across = axis.cross(direction()).normalized()
      let (a, b, c) = (
        Vector3<S>(centre - axis * (size / 2)),
        Vector3<S>(centre + axis * (size / 2)),
        Vector3<S>(
          centre + axis * (size * (uniform() - 0.5)) + across * (size * aspect))
      )
      let needsPlane = TrianglePlane.needsExactT(relative: (a, b, c))
      let (da, db, dc) = (
        Vector3<Double>(a), Vector3<Double>(b), Vector3<Double>(c)
      )
      for _ in 0..<4 {
        var (r1, r2) = (0.05 + 0.9 * uniform(), 0.05 + 0.9 * uniform())
        if r1 + r2 > 1 { (r1, r2) = (1 - r1, 1 - r2) }
        let d = Vector3<S>((da + (db - da) * r1 + (dc - da) * r2).normalized())
        let exactDirection = Vector3<Double>(d)
        guard
          let exact = exactTriangleT(
            da, db, dc, origin: .zero, direction: exactDirection),
          Swift.min(exact.weights.0, exact.weights.1, exact.weights.2) > 0.01,
          let hit = TriangleIntersection.intersect(
            WatertightRay(Ray(origin: .zero, direction: d)), a, b, c,
            after: -.infinity, before: .infinity)
        else { continue }
        let ulps =
          ((Double(hit.t) - exact.hi) - exact.lo).magnitude
          / Double(S(exact.hi).ulp)
        let normal = (db - da).cross(dc - da).normalized()
        let cosine = normal.dot(exactDirection).magnitude
        if needsPlane {
          replaced = Swift.max(replaced, ulps * cosine)
        } else {
          kept = Swift.max(kept, ulps * cosine)
          count += 1
        }
      }
    }
    print(
      "WatertightError \(S.self): kept worst \(kept) ulps·cos θ over \(count) "
        + "rays; replaced worst \(replaced)"
    )
    XCTAssertGreaterThan(count, triangles / 3)
    XCTAssertLessThanOrEqual(kept, 5, "\(S.self)")
    XCTAssertGreaterThan(replaced, 20, "\(S.self): the planes are needed")
  }

  func testFloat() { check(Float.self) }
  func testDouble() { check(Double.self) }
}
