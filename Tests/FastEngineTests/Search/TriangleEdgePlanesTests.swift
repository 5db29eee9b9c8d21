import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `TriangleEdgePlanes`, the screen tiles' first look at a ray: a ray it
/// excludes must be one the watertight test misses. The rays graze an edge
/// or a corner from outside and inside at angles from a thousandth of an ε
/// to far past the margin, for triangles seen at every angular size, from
/// eyes near and far from the origin, in both precisions.
final class TriangleEdgePlanesTests: XCTestCase {
  func testExcludedRaysMissTheWatertightTest() {
    checkExcludedRaysMiss(Float.self, base: 0xED6E_F1)
    checkExcludedRaysMiss(Double.self, base: 0xED6E_D1)
  }

  func checkExcludedRaysMiss<S: RayScalar>(_: S.Type, base: UInt64) {
    var (excludedNearEdges, grazing) = (0, 0)
    var (excludedSquareLines, squareLines) = (0, 0)
    forEachSeed(400, base: base) { generator, _ in
      // An eye anywhere from the origin to 10⁴ away, a triangle at a
      // distance of 10⁻² to 10⁴ seen at an angular size of 10⁻⁴ to 2.
      let eye = Vector3<S>(
        generator.unitVector(Double.self)
          * generator.logUniform(1e-3, 1e4))
      let distance: Double = generator.logUniform(1e-2, 1e4)
      let size = distance * generator.logUniform(1e-4, 2.0)
      let centre =
        Vector3<Double>(eye) + generator.unitVector(Double.self) * distance
      let corners = (0..<3).map { _ in
        Vector3<S>(centre + generator.unitVector(Double.self) * size)
      }
      let (v0, v1, v2) = (corners[0], corners[1], corners[2])
      guard
        let planes = TriangleEdgePlanes(v0, v1, v2, origin: eye)
      else { return XCTFail("finite triangle without planes") }
      for _ in 0..<64 {
        // A point on an edge (or at a corner), seen from the eye, then
        // turned off it by an angle of 10⁻³ to 10⁸ ε (at most ½) either
        // way.
        let edge = Int.random(in: 0..<3, using: &generator)
        let (p, q) = [(v1, v2), (v2, v0), (v0, v1)][edge]
        let along: Double =
          Bool.random(using: &generator) ? 0 : generator.uniform(0...1)
        let point =
          Vector3<Double>(p) * (1 - along) + Vector3<Double>(q) * along
        let toward = (point - Vector3<Double>(eye)).normalized()
        let turn =
          Swift.min(generator.logUniform(1e-3, 1e8) * Double(S.ulpOfOne), 0.5)
          * generator.sign(Double.self)
        let aside = generator.unitVector(Double.self)
        let direction = Vector3<S>(
          (toward + (aside - toward * aside.dot(toward)) * turn).normalized())
        grazing += 1
        guard planes.excludes(direction) else { continue }
        excludedNearEdges += 1
        let ray = WatertightRay(Ray(origin: eye, direction: direction))
        XCTAssertNil(
          TriangleIntersection.edgeFunctions(
            ray, PermutedTriangle(ray, v0, v1, v2)),
          "excluded a ray the watertight test finds inside: \(S.self) "
            + "eye \(eye), corners \(v0) \(v1) \(v2), direction \(direction)")
      }
      // A line square to the one to the triangle's centre passes far
      // outside a triangle seen within 30°; it is excluded unless it lies
      // near the plane of an edge (a sliver's long edges) or the margins
      // (256 ε of the corners' distances squared) are wide for the
      // triangle's angular size.
      if size <= distance / 2, size >= 0x1p12 * Double(S.ulpOfOne) * distance {
        let toward = (centre - Vector3<Double>(eye)).normalized()
        let aside = generator.unitVector(Double.self)
        let square = Vector3<S>(
          (aside - toward * aside.dot(toward)).normalized())
        squareLines += 1
        if planes.excludes(square) { excludedSquareLines += 1 }
      }
    }
    // The test means something only if near-edge rays were excluded.
    XCTAssertGreaterThan(excludedNearEdges, grazing / 8)
    XCTAssertGreaterThan(excludedSquareLines, squareLines * 9 / 10)
  }

  /// Nothing is excluded when the products could overflow.
  func testNoPlanesWhereMarginsOverflow() {
    let huge = Vector3<Double>(1e200, 0, 0)
    XCTAssertNil(
      TriangleEdgePlanes(
        huge, Vector3(0, 1e200, 0), Vector3(0, 0, 1e200), origin: .zero))
    XCTAssertNotNil(
      TriangleEdgePlanes(
        Vector3<Double>(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1),
        origin: .zero))
  }
}
