import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `TriangleIntersection.covers`, the watertight test without its t, and
/// the bound under which it answers as `intersect` on the whole line does
/// (`LargeTrianglePlane.edgesDecide`).
final class TriangleIntersectionTests: XCTestCase {
  /// Random triangles with vertices up to `extent` from the origin, some
  /// through it and some beside it, and unit directions: `covers` must
  /// agree with `intersect(…, after: −∞, before: ∞)` on every one. Both
  /// answers must occur, so that neither is always true.
  func checkCoversAgrees<T: RayScalar>(_: T.Type, extent: T) {
    var generator = SplitMix64(seed: 0x7269_616e_676c_6521)
    var (covered, missed) = (0, 0)
    for _ in 0..<20_000 {
      let scale = generator.logUniform(T(1), extent)
      func vertex() -> Vector3<T> {
        Vector3(
          generator.uniform(-1...1), generator.uniform(-1...1),
          generator.uniform(-1...1)) * scale
      }
      let (v0, v1, v2) = (vertex(), vertex(), vertex())
      let ray = WatertightRay(
        Ray(origin: .zero, direction: generator.unitVector(T.self)))
      let whole = TriangleIntersection.intersect(
        ray, v0, v1, v2, after: -.infinity, before: .infinity)
      let covers = TriangleIntersection.covers(ray, v0, v1, v2)
      XCTAssertEqual(covers, whole != nil, "\(T.self): \(v0) \(v1) \(v2)")
      if covers { covered += 1 } else { missed += 1 }
    }
    XCTAssertGreaterThan(covered, 1000, "\(T.self)")
    XCTAssertGreaterThan(missed, 1000, "\(T.self)")
  }

  func testCovers_AgreesWithIntersect_Float() {
    checkCoversAgrees(Float.self, extent: limit(Float.self))
  }

  func testCovers_AgreesWithIntersect_Double() {
    checkCoversAgrees(Double.self, extent: limit(Double.self))
  }

  /// The largest vertex coordinate for which `LargeTrianglePlane` lets the
  /// edges decide: 2^39 in float, 2^338 in double.
  func limit<T: RayScalar>(_: T.Type) -> T {
    let plane = LargeTrianglePlane<T>(
      .init(
        normal: Vector3(0, 1, 0), normalTail: .zero, distance: 1,
        isAxisAligned: true), relative: (.zero, .zero, .zero))
    XCTAssertTrue(plane.edgesDecide)
    return T(
      sign: .plus, exponent: T.greatestFiniteMagnitude.exponent / 3 - 3,
      significand: 1)
  }

  /// At the limit the edges decide; one ulp past it they do not.
  func checkEdgesDecideLimit<T: RayScalar>(_: T.Type) {
    let c = limit(T.self)
    func plane(_ extent: T) -> LargeTrianglePlane<T> {
      LargeTrianglePlane(
        .init(
          normal: Vector3(0, 1, 0), normalTail: .zero, distance: -1,
          isAxisAligned: true),
        relative: (Vector3(-extent, -1, 1), Vector3(1, -1, 1), .zero))
    }
    XCTAssertTrue(plane(c).edgesDecide, "\(T.self)")
    XCTAssertFalse(plane(c.nextUp).edgesDecide, "\(T.self)")
  }

  func testEdgesDecide_Limit_Float() { checkEdgesDecideLimit(Float.self) }
  func testEdgesDecide_Limit_Double() { checkEdgesDecideLimit(Double.self) }

  /// Why the limit exists: far beyond it the weighted sum of z overflows,
  /// `intersect` misses (t is not finite) while the edges accept the ray.
  func testCovers_DiffersWhereTOverflows() {
    let big = Float.greatestFiniteMagnitude / 4
    let (v0, v1, v2) = (
      Vector3<Float>(-big, -big, big), Vector3<Float>(big, -big, big),
      Vector3<Float>(0, big, big)
    )
    let ray = WatertightRay(
      Ray(origin: .zero, direction: Vector3<Float>(0, 0, 1)))
    XCTAssertTrue(TriangleIntersection.covers(ray, v0, v1, v2))
    XCTAssertNil(
      TriangleIntersection.intersect(
        ray, v0, v1, v2, after: -.infinity, before: .infinity))
  }

  /// `sharesFrame` holds exactly when two rays have one permutation and one
  /// origin, zeros' signs included; a triangle permuted for one ray then
  /// gives every other ray sharing its frame the bits of the ray's own
  /// test (the screen tiles permute each triangle once per tile). Rays
  /// that do not share it must be seen not to: permuted for the wrong
  /// frame, their tests differ.
  func checkSharedFrame<T: RayScalar>(_: T.Type) {
    var generator = SplitMix64(seed: 0x7065_726d_7574_6521)
    var (shared, differs) = (0, 0)
    for _ in 0..<20_000 {
      func point(_ scale: T) -> Vector3<T> {
        Vector3(
          generator.uniform(-1...1), generator.uniform(-1...1),
          generator.uniform(-1...1)) * scale
      }
      let origin = point(2)
      let toward = point(1) + Vector3(0, 0, 3)
      let (v0, v1, v2) = (
        toward + point(1), toward + point(1), toward + point(1)
      )
      // Directions toward the triangle, most with the same largest axis.
      func ray() -> WatertightRay<T> {
        WatertightRay(
          Ray(
            origin: origin,
            direction: (toward + point(3) - origin).normalized()))
      }
      let (first, second) = (ray(), ray())
      let same =
        first.kx == second.kx && first.ky == second.ky && first.kz == second.kz
      XCTAssertEqual(first.sharesFrame(with: second), same, "\(T.self)")
      let own = TriangleIntersection.intersect(
        second, v0, v1, v2, after: 0, before: .infinity)
      let borrowed = TriangleIntersection.intersect(
        second, PermutedTriangle(first, v0, v1, v2), after: 0,
        before: .infinity)
      if same {
        shared += 1
        // The same bits: each value equal and of the same sign (a zero's
        // too), a miss for both or neither.
        func bits(_ hit: (t: T, u: T, v: T, w: T)?) -> [String] {
          hit.map { [$0.t, $0.u, $0.v, $0.w].map { "\($0) \($0.sign)" } }
            ?? []
        }
        XCTAssertEqual(bits(own), bits(borrowed), "\(T.self)")
      } else if own?.t != borrowed?.t {
        differs += 1
      }
    }
    XCTAssertGreaterThan(shared, 5_000, "\(T.self)")
    XCTAssertGreaterThan(differs, 100, "\(T.self)")
    // The same permutation from origins +0 and −0 is not one frame.
    let direction = Vector3<T>(0.1, 0.2, 1).normalized()
    let plus = WatertightRay(Ray(origin: Vector3<T>.zero, direction: direction))
    let minus = WatertightRay(
      Ray(origin: Vector3<T>(-0.0, 0, 0), direction: direction))
    XCTAssertTrue(plus.sharesFrame(with: plus))
    XCTAssertFalse(plus.sharesFrame(with: minus))
  }

  func testSharedFrame_Float() { checkSharedFrame(Float.self) }
  func testSharedFrame_Double() { checkSharedFrame(Double.self) }
}
