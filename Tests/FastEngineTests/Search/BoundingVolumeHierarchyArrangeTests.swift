import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

final class BoundingVolumeHierarchyArrangeTests: XCTestCase {
  typealias BVH = BoundingVolumeHierarchy<Double>

  /// Random boxes from a seeded generator.
  func boxes(
    _ count: Int, seed: UInt64
  ) -> [(lower: Vector3<Double>, upper: Vector3<Double>)] {
    var generator = SplitMix64(seed: seed)
    return (0..<count).map { _ in
      let center =
        generator.unitVector(Double.self) * generator.logUniform(1, 100)
      let half: Double = generator.logUniform(0.01, 2)
      let extent = Vector3(half, half, half)
      return (center - extent, center + extent)
    }
  }

  /// Arranging in place gives what `order.map` gives, for every seed.
  func testArrange_MatchesMappingThroughTheOrder() {
    for seed: UInt64 in 1...20 {
      let count = Int(seed) * 97
      let hierarchy = BVH(boxes: boxes(count, seed: seed))
      let original = (0..<count).map { "element \($0)" }
      var arranged = original
      hierarchy.arrange(&arranged)
      XCTAssertEqual(
        arranged, hierarchy.order.map { original[Int($0)] },
        "seed \(seed)")
    }
  }

  func testArrange_EmptyAndOne() {
    var none: [Int] = []
    BVH(boxes: []).arrange(&none)
    XCTAssertEqual(none, [])
    var one = [7]
    BVH(boxes: boxes(1, seed: 3)).arrange(&one)
    XCTAssertEqual(one, [7])
  }

  /// Boxes given by a closure build the tree that an array of them builds,
  /// on one thread or two.
  func testBuildFromClosure_MatchesBuildFromArray() {
    let given = boxes(5000, seed: 0xB0C5)
    let fromArray = BVH(boxes: given, concurrentFrom: .max)
    for concurrentFrom in [100, Int.max] {
      let fromClosure = BVH(count: given.count, concurrentFrom: concurrentFrom)
      { given[$0] }
      XCTAssertEqual(fromArray.nodes, fromClosure.nodes)
      XCTAssertEqual(fromArray.order, fromClosure.order)
      XCTAssertEqual(fromArray.depth, fromClosure.depth)
    }
  }

  /// A random triangle soup, compiled as `CompiledScene` compiles it (the
  /// records arranged in place into leaf order), gives the nearest hit of
  /// testing every triangle in the original order: the same t and the same
  /// triangle, ties to the first.
  func testArrangedTriangles_NearestMatchesBruteForce() throws {
    try skipUnlessLongTests()
    for seed: UInt64 in [0x7121, 0x7122, 0x7123] {
      var generator = SplitMix64(seed: seed)
      var records: [TriangleRecord<Double>] = []
      for _ in 0..<3000 {
        let center =
          generator.unitVector(Double.self) * generator.logUniform(1, 20)
        let size: Double = generator.logUniform(0.05, 3)
        func corner() -> Vector3<Double> {
          center + generator.unitVector(Double.self) * size
        }
        records.append(
          TriangleRecord(v0: corner(), v1: corner(), v2: corner()))
      }
      // A few exact duplicates, so that ties occur.
      for index in stride(from: 0, to: 300, by: 10) {
        records.append(records[index])
      }
      let hierarchy = BVH(count: records.count, concurrentFrom: 1000) {
        let r = records[$0]
        let lower = Vector3(
          Swift.min(r.v0.x, r.v1.x, r.v2.x), Swift.min(r.v0.y, r.v1.y, r.v2.y),
          Swift.min(r.v0.z, r.v1.z, r.v2.z))
        let upper = Vector3(
          Swift.max(r.v0.x, r.v1.x, r.v2.x), Swift.max(r.v0.y, r.v1.y, r.v2.y),
          Swift.max(r.v0.z, r.v1.z, r.v2.z))
        let pad =
          4 * Double.ulpOfOne
          * Swift.max(lower.maxMagnitude, upper.maxMagnitude)
        let padding = Vector3(pad, pad, pad)
        return (lower - padding, upper + padding)
      }
      var arranged = records
      hierarchy.arrange(&arranged)
      let wide = WideHierarchy(hierarchy, rayOrigin: .zero)
      for rayIndex in 0..<500 {
        let direction = generator.unitVector(Double.self)
        let ray = CameraRay<Double>(origin: .zero, direction: direction)
        let prepared = WatertightRay(
          Ray(origin: ray.origin, direction: ray.direction))
        var best: (t: Double, index: Int)?
        for index in records.indices {
          if let hit = records[index].intersect(
            prepared, before: best?.t ?? .infinity)
          {
            best = (hit.t, index)
          }
        }
        let found = arranged.withUnsafeBufferPointer {
          hierarchy.nearest(
            ray, before: .infinity,
            leaves: TriangleLeaves(records: $0, ray: prepared), wide: wide)
        }
        XCTAssertEqual(
          found?.t, best?.t, "seed \(seed), ray \(rayIndex)")
        XCTAssertEqual(
          found.map { Int(hierarchy.order[$0.index]) }, best?.index,
          "seed \(seed), ray \(rayIndex)")
      }
    }
  }
}
