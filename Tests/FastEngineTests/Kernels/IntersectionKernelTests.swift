import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

final class IntersectionKernelTests: XCTestCase {
  /// The flat searches keep what the stable test computed on its way to t
  /// (`SphereHitMemo`, the closest approach) and give it to the normal,
  /// which would otherwise compute the same values again. Over spheres
  /// from a tenth of a radius (the eye inside) to 10⁸ radii away, each hit's
  /// normal from the memo must be the
  /// normal computed afresh, bit for bit, whichever form the test took;
  /// both forms must occur, so that the memo is exercised and its absence
  /// too.
  func checkMemoGivesTheSameNormal<T: RayScalar>(_: T.Type) {
    var generator = SplitMix64(seed: 0x3E30)
    var (withMemo, withoutMemo) = (0, 0)
    for _ in 0..<4000 {
      let distance: Double = generator.logUniform(0.1, 1e8)
      let direction: Vector3<Double> = generator.unitVector()
      let sphere = Sphere<Double>(
        center: direction * distance, radius: 1, materialIndex: 0)
      let record = StableKernel<T>.makeSphere(sphere, eye: .zero)
      // Aimed within the sphere's silhouette: mostly hits.
      let aim =
        direction * distance
        + generator.unitVector() * generator.uniform(0...0.99)
      let ray = CameraRay<T>(
        origin: .zero, direction: Vector3<T>(aim.normalized()))
      var memo = StableKernel<T>.noMemo
      guard
        let t = StableKernel<T>.intersect(
          record, ray, before: .infinity, memo: &memo)
      else { continue }
      XCTAssertEqual(
        StableKernel<T>.intersect(record, ray, before: .infinity), t)
      if memo == nil { withoutMemo += 1 } else { withMemo += 1 }
      let fresh = StableKernel<T>.normal(record, ray, t: t)
      let remembered = StableKernel<T>.normal(record, ray, t: t, memo: memo)
      for (a, b) in [
        (fresh.x, remembered.x), (fresh.y, remembered.y),
        (fresh.z, remembered.z),
      ]
      where a.sign != b.sign || a.exponentBitPattern != b.exponentBitPattern
        || a.significandBitPattern != b.significandBitPattern
      {
        XCTFail("\(T.self) at \(distance) radii: \(fresh) ≠ \(remembered)")
        return
      }
    }
    XCTAssertGreaterThan(withMemo, 100, "\(T.self): far form")
    XCTAssertGreaterThan(withoutMemo, 100, "\(T.self): near form")
  }

  func testSphereMemo_SameNormal_Float() {
    checkMemoGivesTheSameNormal(Float.self)
  }

  func testSphereMemo_SameNormal_Double() {
    checkMemoGivesTheSameNormal(Double.self)
  }
}

extension SphereIntersection.ClosestApproach: Equatable {
  public static func == (a: Self, b: Self) -> Bool {
    a.offset == b.offset && a.root == b.root
  }
}
