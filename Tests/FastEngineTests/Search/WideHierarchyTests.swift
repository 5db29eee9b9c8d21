import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The wide hierarchy's own guarantees. That it answers exactly as testing
/// every sphere does is checked with the binary hierarchy's fixtures
/// (`BoundingVolumeHierarchyTests`, whose `nearest` goes through it).
final class WideHierarchyTests: XCTestCase {
  typealias Fixture = BoundingVolumeHierarchyTests.Fixture

  func randomSpheres(_ count: Int, seed: UInt64, spread: Double = 10)
    -> [Sphere<Double>]
  {
    var generator = SplitMix64(seed: seed)
    return (0..<count).map { _ in
      Sphere(
        center: Vector3(
          generator.uniform(-spread...spread),
          generator.uniform(-spread...spread),
          generator.uniform(-spread...spread)),
        radius: generator.uniform(0.05...0.5))
    }
  }

  /// Every primitive sits in exactly one leaf, each child's Float box holds
  /// the binary node's box relative to the origin, and empty slots are
  /// boxes no ray enters.
  func checkStructure<Scalar: RayScalar>(
    _ wide: WideHierarchy<Scalar>, _ binary: BoundingVolumeHierarchy<Scalar>,
    origin: Vector3<Scalar>, file: StaticString = #filePath, line: UInt = #line
  ) {
    var seen = [Int](repeating: 0, count: binary.order.count)
    var nodesSeen = 0
    func visit(_ reference: Int32) {
      if reference < 0 {
        let leaf = ~reference
        let first = Int(leaf >> 3)
        for position in first..<(first + Int(leaf & 7)) { seen[position] += 1 }
        return
      }
      nodesSeen += 1
      let node = wide.nodes[Int(reference)]
      for lane in 0..<4 {
        let lower = SIMD3(
          node.lowerX[lane], node.lowerY[lane], node.lowerZ[lane])
        let upper = SIMD3(
          node.upperX[lane], node.upperY[lane], node.upperZ[lane])
        if lower.x > upper.x {
          XCTAssertEqual(
            node.children[lane], 0, "an empty slot", file: file, line: line)
          continue
        }
        visit(node.children[lane])
      }
    }
    visit(wide.root)
    XCTAssertEqual(
      nodesSeen, wide.nodes.count, "every wide node is reachable", file: file,
      line: line)
    XCTAssertEqual(
      seen, Array(repeating: 1, count: seen.count),
      "each primitive in one leaf", file: file, line: line)
    // Every binary leaf's box, relative to the origin, lies inside the
    // Float box of the wide child that holds it.
    var leafBoxes: [Int: (lower: SIMD3<Float>, upper: SIMD3<Float>)] = [:]
    for node in wide.nodes {
      for lane in 0..<4 where node.children[lane] < 0 {
        let first = Int(~node.children[lane] >> 3)
        leafBoxes[first] = (
          SIMD3(node.lowerX[lane], node.lowerY[lane], node.lowerZ[lane]),
          SIMD3(node.upperX[lane], node.upperY[lane], node.upperZ[lane])
        )
      }
    }
    for node in binary.nodes where node.isLeaf {
      guard let box = leafBoxes[Int(node.index)] else {
        XCTFail(
          "leaf at \(node.index) not in the wide hierarchy", file: file,
          line: line)
        continue
      }
      let lower = node.lower - origin
      let upper = node.upper - origin
      for (float, exact) in zip(
        [box.lower.x, box.lower.y, box.lower.z], [lower.x, lower.y, lower.z])
      {
        XCTAssertLessThanOrEqual(Scalar(float), exact, file: file, line: line)
      }
      for (float, exact) in zip(
        [box.upper.x, box.upper.y, box.upper.z], [upper.x, upper.y, upper.z])
      {
        XCTAssertGreaterThanOrEqual(
          Scalar(float), exact, file: file, line: line)
      }
    }
  }

  func testStructure_RandomScenes() {
    for (count, seed) in [(12, 1), (100, 2), (2_000, 3)] as [(Int, UInt64)] {
      let spheres = randomSpheres(count, seed: seed)
      let eye = Vector3<Double>(0.3, 1.7, 30)
      let stable = Fixture<StableKernel<Double>>(spheres, eye: eye)
      guard let wide = stable.wide else {
        return XCTFail("declined \(count) spheres")
      }
      checkStructure(wide, stable.hierarchy, origin: stable.origin)
      let naive = Fixture<NaiveKernel<Float>>(spheres, eye: eye)
      guard let wideNaive = naive.wide else {
        return XCTFail("declined \(count) spheres")
      }
      checkStructure(wideNaive, naive.hierarchy, origin: naive.origin)
    }
  }

  /// The wide tree is never deeper than the binary one, so its stack of
  /// three deferred children per level fits.
  func testDepth_WithinStack() {
    let spheres = randomSpheres(5_000, seed: 4)
    let fixture = Fixture<StableKernel<Float>>(spheres, eye: Vector3(0, 0, 40))
    guard let wide = fixture.wide else { return XCTFail("declined") }
    func depth(_ reference: Int32) -> Int {
      guard reference >= 0 else { return 0 }
      let node = wide.nodes[Int(reference)]
      let filled = (0..<4).filter { node.lowerX[$0] <= node.upperX[$0] }
      return 1 + filled.map { depth(node.children[$0]) }.max()!
    }
    XCTAssertLessThanOrEqual(depth(wide.root), fixture.hierarchy.depth)
    XCTAssertLessThanOrEqual(
      3 * fixture.hierarchy.depth + 1, WideHierarchy<Float>.stackCapacity)
  }

  /// Faces beyond 2⁶⁰ from the eye could overflow Float's slab distances:
  /// the wide hierarchy declines and the binary one answers.
  func testDeclines_BeyondCoordinateLimit() {
    var spheres = randomSpheres(40, seed: 5)
    spheres.append(Sphere(center: Vector3(0x1p61, 0, 0), radius: 1))
    let fixture = Fixture<StableKernel<Double>>(spheres, eye: Vector3(0, 0, 30))
    XCTAssertNil(fixture.wide)
    fixture.checkMatches([
      Vector3(0, 0, -1), Vector3(1, 0, 0), Vector3(0.1, 0.2, -1).normalized(),
    ])
  }

  /// Directions with a component between 0 and 2⁻⁴⁰ are unsuitable; the
  /// combined answer still equals brute force for them.
  func testUnsuitable_TinyDirectionComponents() {
    let spheres = randomSpheres(200, seed: 6, spread: 3)
    let fixture = Fixture<StableKernel<Double>>(spheres, eye: Vector3(0, 0, 20))
    guard let wide = fixture.wide else { return XCTFail("declined") }
    let tiny = Vector3<Double>(0x1p-50, -0x1p-45, -1)
    let answer = fixture.ordered.withUnsafeBufferPointer { records in
      wide.nearest(
        fixture.ray(tiny), before: .infinity,
        leaves: SphereLeaves<StableKernel<Double>>(
          records: records, ray: fixture.ray(tiny)))
    }
    guard case .unsuitable = answer else {
      return XCTFail("answered \(answer)")
    }
    var directions = [tiny, Vector3(0, 0, -1), Vector3(-0.0, 0x1p-40, -1)]
    var generator = SplitMix64(seed: 7)
    for _ in 0..<400 {
      directions.append(
        Vector3<Double>(
          generator.uniform(-0.15...0.15), generator.uniform(-0.15...0.15), -1
        ).normalized())
    }
    XCTAssertGreaterThan(fixture.checkMatches(directions), 50, "most rays hit")
  }

  /// Rays parallel to a box face and 10⁻¹⁰ radii inside it: each sphere
  /// is placed so that its extreme point along ±x or ±y lies just beyond
  /// the eye's coordinate there, and a ray with that direction component
  /// exactly 0 (an infinite reciprocal on the wide path) crosses the cap
  /// between. Faces are stored relative to the eye, so the Float rounding
  /// cannot move such a face across the ray; what this checks is the
  /// zero-component slab arithmetic next to a face
  /// (`testStructure_RandomScenes` is what catches inward rounding).
  func testNearest_RaysParallelToFacesJustInside() {
    func check<Kernel: IntersectionKernel>(_: Kernel.Type) {
      var generator = SplitMix64(seed: 8)
      let eye = Vector3<Double>(0.123456789, -0.0987654321, 7.77)
      var spheres: [Sphere<Double>] = []
      var directions: [Vector3<Kernel.Scalar>] = []
      for index in 0..<400 {
        let radius: Double = generator.uniform(0.1...0.9)
        let inset = radius * (1 - 1e-10)
        var center = Vector3<Double>(
          eye.x + generator.uniform(-6.0...6.0),
          eye.y + generator.uniform(-6.0...6.0),
          generator.uniform(-30.0 ... -10.0))
        switch index % 4 {
        case 0: center.x = eye.x - inset
        case 1: center.x = eye.x + inset
        case 2: center.y = eye.y - inset
        default: center.y = eye.y + inset
        }
        spheres.append(Sphere(center: center, radius: radius))
        var toward = center - eye
        if index % 4 < 2 { toward.x = 0 } else { toward.y = 0 }
        directions.append(Vector3(toward.normalized()))
      }
      let fixture = Fixture<Kernel>(spheres, eye: eye)
      XCTAssertNotNil(fixture.wide)
      let hits = fixture.checkMatches(directions, "\(Kernel.self)")
      XCTAssertGreaterThan(
        hits, directions.count / 2, "\(Kernel.self): most rays hit")
    }
    check(StableKernel<Double>.self)
    check(NaiveKernel<Double>.self)
  }
}
