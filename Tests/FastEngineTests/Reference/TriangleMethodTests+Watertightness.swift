import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension TriangleMethodTests {
  // MARK: - Watertightness

  /// A fan of 7 to 16 triangles around a shared centre, in a random plane
  /// and position; rays from random origins aimed exactly at the centre
  /// vertex or at points of the shared spokes must hit at least one
  /// triangle: the fan has no gap for a ray to leak through.
  func checkWatertightFan<T: RayScalar>(_: T.Type) {
    var leaksOfPlainTest = 0
    forEachSeed(300, base: 0x7121_0002) { generator, seed in
      let frame = randomFrame(using: &generator)
      let count = Int.random(in: 7...16, using: &generator)
      let centre = Vector3<T>(
        frame.point(
          generator.uniform(-0.1...0.1), generator.uniform(-0.1...0.1)))
      var ring: [Vector3<T>] = []
      for index in 0..<count {
        let angle =
          (Double(index) + generator.uniform(-0.3...0.3)) * 2 * .pi
          / Double(count)
        let radius: Double = generator.uniform(0.5...2)
        ring.append(
          Vector3<T>(frame.point(radius * cos(angle), radius * sin(angle))))
      }
      let triangles = (0..<count).map {
        Triangle(centre, ring[$0], ring[($0 + 1) % count])
      }
      for _ in 0..<20 {
        let spoke = ring[Int.random(in: 0..<count, using: &generator)]
        let s: Double =
          Bool.random(using: &generator) ? 0 : generator.uniform(0...0.9)
        let target =
          Vector3<Double>(centre)
          + (Vector3<Double>(spoke) - Vector3<Double>(centre)) * s
        leaksOfPlainTest += checkNoLeak(
          triangles, target: target, frame: frame, seed: seed, using: &generator
        )
      }
    }
    print(
      "\(T.self) fan: rays leaking through a plain Möller–Trumbore test: "
        + "\(leaksOfPlainTest)")
    XCTAssertGreaterThan(
      leaksOfPlainTest, 0,
      "\(T.self): the rays should find the gaps a non-watertight test leaves")
  }

  func testWatertight_Fan_Float() { checkWatertightFan(Float.self) }
  func testWatertight_Fan_Double() { checkWatertightFan(Double.self) }

  /// A 6×6 grid of jittered quads, each split along a random diagonal, in
  /// a random plane and position; rays aimed exactly at interior vertices
  /// and at points of interior edges must hit at least one triangle.
  func checkWatertightGrid<T: RayScalar>(_: T.Type) {
    var leaksOfPlainTest = 0
    let cells = 6
    forEachSeed(60, base: 0x7121_0003) { generator, seed in
      let frame = randomFrame(using: &generator)
      var grid: [[Vector3<T>]] = []
      for i in 0...cells {
        var row: [Vector3<T>] = []
        for j in 0...cells {
          let interior = i > 0 && i < cells && j > 0 && j < cells
          let jitter: Double = interior ? 0.3 : 0
          row.append(
            Vector3<T>(
              frame.point(
                (Double(i) + generator.uniform(-jitter...jitter))
                  / Double(cells) * 2 - 1,
                (Double(j) + generator.uniform(-jitter...jitter))
                  / Double(cells) * 2 - 1)))
        }
        grid.append(row)
      }
      var triangles: [Triangle<T>] = []
      // Edges shared by two triangles, as vertex pairs.
      var interiorEdges: [(Vector3<T>, Vector3<T>)] = []
      for i in 0..<cells {
        for j in 0..<cells {
          let a = grid[i][j]
          let b = grid[i + 1][j]
          let c = grid[i + 1][j + 1]
          let d = grid[i][j + 1]
          if Bool.random(using: &generator) {
            triangles += [Triangle(a, b, c), Triangle(a, c, d)]
            interiorEdges.append((a, c))
          } else {
            triangles += [Triangle(a, b, d), Triangle(b, c, d)]
            interiorEdges.append((b, d))
          }
          if i > 0 { interiorEdges.append((a, d)) }
          if j > 0 { interiorEdges.append((a, b)) }
        }
      }
      for _ in 0..<40 {
        let target: Vector3<Double>
        if Bool.random(using: &generator) {
          let i = Int.random(in: 1..<cells, using: &generator)
          let j = Int.random(in: 1..<cells, using: &generator)
          target = Vector3<Double>(grid[i][j])
        } else {
          let edge = interiorEdges[
            Int.random(in: 0..<interiorEdges.count, using: &generator)]
          let s: Double = generator.uniform(0...1)
          target =
            Vector3<Double>(edge.0)
            + (Vector3<Double>(edge.1) - Vector3<Double>(edge.0)) * s
        }
        leaksOfPlainTest += checkNoLeak(
          triangles, target: target, frame: frame, seed: seed, using: &generator
        )
      }
    }
    print(
      "\(T.self) grid: rays leaking through a plain Möller–Trumbore test: "
        + "\(leaksOfPlainTest)")
    XCTAssertGreaterThan(
      leaksOfPlainTest, 0,
      "\(T.self): the rays should find the gaps a non-watertight test leaves")
  }

  func testWatertight_Grid_Float() { checkWatertightGrid(Float.self) }
  func testWatertight_Grid_Double() { checkWatertightGrid(Double.self) }

  /// Casts one ray from a random origin (distance log-uniform in [0.5,
  /// 1000] mesh sizes, at least 0.05 in cosine from the plane, so that the
  /// rounding of the direction cannot carry the ray off the mesh) through
  /// `target`, and fails if no triangle is hit. Returns 1 when a plain
  /// Möller–Trumbore test in the same precision misses every triangle, to
  /// show that the rays probe the gaps such a test leaves.
  func checkNoLeak<T: RayScalar>(
    _ triangles: [Triangle<T>], target: Vector3<Double>, frame: Frame,
    seed: UInt64, using generator: inout SplitMix64
  ) -> Int {
    var direction = generator.unitVector(Double.self)
    while abs(direction.dot(frame.normal)) < 0.05 {
      direction = generator.unitVector(Double.self)
    }
    let distance: Double = generator.logUniform(0.5, 1000)
    let origin = Vector3<T>(target - direction * distance)
    let ray = Ray(origin: origin, direction: Vector3<T>(target) - origin)
    let prepared = WatertightRay(ray)
    let hits = triangles.filter {
      TriangleIntersection.intersect(
        prepared, $0.v0, $0.v1, $0.v2, after: 0, before: .infinity) != nil
    }
    XCTAssertFalse(
      hits.isEmpty,
      "\(T.self) seed \(seed): \(ray) leaks through the mesh at \(target)")
    return triangles.contains { mollerTrumbore(ray, $0) } ? 0 : 1
  }
}
