import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension BoundingVolumeHierarchyTests {
  // MARK: - Through CompiledScene

  /// A compiled scene with the hierarchy finds what the same scene without
  /// it finds, planes included, for every ray of a small render's camera.
  func checkCompiledScene<Kernel: IntersectionKernel>(
    _: Kernel.Type, base: UInt64
  ) {
    forEachSeed(6, base: base) { generator, _ in
      let (spheres, eye) = randomScene(&generator, count: 150)
      var objects = spheres.map { SceneObject<Double>.sphere($0) }
      objects.append(
        .plane(Plane(normal: Vector3(0, 1, 0), offset: spheres[0].center.y)))
      let target = spheres[1].center
      guard
        let camera = PerspectiveCamera<Double>(
          center: eye, direction: target - eye, up: Vector3(0, 1, 0.1),
          angle: 40)
      else { return }
      let scene = Scene(camera: camera, root: Group(objects))
      let flat = CompiledScene<Kernel>(scene, hierarchyThreshold: .max)
      let tree = CompiledScene<Kernel>(scene, hierarchyThreshold: 0)
      XCTAssertFalse(flat.usesHierarchy)
      XCTAssertTrue(tree.usesHierarchy)
      guard let order = tree.hierarchy?.order else { return }
      let cameraInPrecision = PerspectiveCamera<Kernel.Scalar>(camera)
      var mismatches = 0
      for row in 0..<24 {
        for column in 0..<24 {
          let x = Kernel.Scalar(column) / 12 - 1
          let y = Kernel.Scalar(row) / 12 - 1
          let ray = CameraRay(
            origin: flat.rayOrigin,
            direction: cameraInPrecision.rayDirection(x: x, y: y, aspect: 1))
          let want = flat.nearest(ray)
          let got = tree.nearest(ray)
          var same = want?.t == got?.t
          switch (want?.what, got?.what) {
          case (.sphere(let a)?, .sphere(let b)?):
            same = same && a == Int(order[b])
          case (.plane(let a)?, .plane(let b)?): same = same && a == b
          case (nil, nil): break
          default: same = false
          }
          if !same { mismatches += 1 }
        }
      }
      XCTAssertEqual(mismatches, 0, "\(Kernel.self)")
    }
  }

  func testCompiledScene_HierarchyMatchesFlatLoop() {
    checkCompiledScene(StableKernel<Float>.self, base: 0xC5F)
    checkCompiledScene(NaiveKernel<Double>.self, base: 0xC6D)
    guard runsLongTests else { return }
    checkCompiledScene(StableKernel<Double>.self, base: 0xC5D)
    checkCompiledScene(NaiveKernel<Float>.self, base: 0xC6F)
  }

  func testDefaultThreshold_IsMoreThanAHandful() {
    XCTAssertGreaterThanOrEqual(
      BoundingVolumeHierarchy<Float>.defaultThreshold, 8)
    XCTAssertGreaterThanOrEqual(
      BoundingVolumeHierarchy<Double>.defaultThreshold, 8)
  }
}
