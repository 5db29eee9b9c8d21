import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `SphereIntersection.stableRoot` on spheres behind the ray's origin, and
/// the flat searches' shortcut for them (`StableKernel.intersect(…memo:)`).
final class SphereIntersectionTests: XCTestCase {
  /// A sphere behind the ray's origin (centre behind, origin outside): the
  /// root from tMin = 0 is none, the kernel's shortcut says so before the
  /// discriminant, and from tMin = −∞ the full computation still finds the
  /// nearer of its two negative roots, the entering one, within a few ulps
  /// of the reference; so the shortcut holds only for searches from 0.
  func checkSphereBehind<T: RayScalar>(_: T.Type) throws {
    var generator = SplitMix64(seed: 0x6265_6869_6e64)
    for _ in 0..<2_000 {
      let direction = generator.unitVector(T.self)
      let radius: T = generator.logUniform(T(0.01), T(100))
      // The centre behind the origin, up to a few radii off the line,
      // the origin outside.
      let along: T = -generator.logUniform(T(1.1) * radius, T(1000) * radius)
      let across = generator.unitVector(T.self).cross(direction) * radius
      let center = direction * along + across
      let sphere = Sphere<T>(center: center, radius: radius)
      let relative = CameraRelative.sphere(
        center: center, radius: radius, eye: Vector3<T>.zero, as: T.self)
      guard relative.c > 0 else { continue }
      let a = direction.lengthSquared
      func root(after tMin: T) -> (t: T, entering: Bool)? {
        SphereIntersection.stableRoot(
          direction: direction, lengthSquared: a,
          inverseLengthSquared: SphereIntersection.inverseLengthSquared(a),
          offset: relative.offset, c: relative.c,
          radiusSquared: radius * radius, after: tMin, before: .infinity)
      }
      XCTAssertNil(root(after: 0), "\(T.self): behind the origin")
      let record = StableKernel<T>.SphereRecord(
        offset: relative.offset, radiusSquared: radius * radius,
        c: relative.c, inverseRadius: 1 / radius)
      var memo = StableKernel<T>.noMemo
      XCTAssertNil(
        StableKernel<T>.intersect(
          record, CameraRay(origin: .zero, direction: direction),
          before: .infinity, memo: &memo))
      // The same sphere ahead: the shortcut lets it through.
      let ahead = CameraRelative.sphere(
        center: -center, radius: radius, eye: Vector3<T>.zero, as: T.self)
      let aheadRecord = StableKernel<T>.SphereRecord(
        offset: ahead.offset, radiusSquared: radius * radius, c: ahead.c,
        inverseRadius: 1 / radius)
      XCTAssertEqual(
        StableKernel<T>.intersect(
          aheadRecord, CameraRay(origin: .zero, direction: direction),
          before: .infinity, memo: &memo),
        SphereIntersection.stableRoot(
          direction: direction, lengthSquared: a,
          inverseLengthSquared: SphereIntersection.inverseLengthSquared(a),
          offset: ahead.offset, c: ahead.c, radiusSquared: radius * radius,
          after: 0, before: .infinity)?.t, "\(T.self): ahead")
      let ray = Ray<T>(origin: .zero, direction: direction)
      guard let want = referenceIntersect(ray, sphere, after: -.infinity)
      else {
        XCTAssertNil(root(after: -.infinity), "\(T.self): the line misses")
        continue
      }
      let behind = try XCTUnwrap(
        root(after: -.infinity), "\(T.self): the line meets the sphere")
      XCTAssertTrue(behind.entering, "\(T.self)")
      // A stable root a few radii or more away: a few roundings, away
      // from tangency (the reference's own discriminant is then well
      // conditioned; tangent lines are left to SphereMethodTests).
      if radius * radius - across.lengthSquared > radius * radius / 100 {
        assertRelativeError(behind.t, want.t, ulps: 8, "behind the origin")
      }
    }
  }

  func testStableRoot_SphereBehind_Float() throws {
    try checkSphereBehind(Float.self)
  }
  func testStableRoot_SphereBehind_Double() throws {
    try checkSphereBehind(Double.self)
  }
}
