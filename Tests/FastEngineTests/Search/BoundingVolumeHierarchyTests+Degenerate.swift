import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension BoundingVolumeHierarchyTests {
  // MARK: - Degenerate input

  func checkAllKernels(
    _ spheres: [Sphere<Double>], eye: Vector3<Double>,
    directions: [Vector3<Double>], _ context: String,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    func check<Kernel: IntersectionKernel>(_: Kernel.Type) {
      let fixture = Fixture<Kernel>(spheres, eye: eye)
      fixture.checkMatches(
        directions.map { Vector3<Kernel.Scalar>($0) }, context,
        file: file, line: line)
      checkStructure(
        fixture.hierarchy, spheres: fixture.records, kernel: Kernel.self,
        file: file, line: line)
    }
    check(StableKernel<Float>.self)
    check(StableKernel<Double>.self)
    check(NaiveKernel<Float>.self)
    check(NaiveKernel<Double>.self)
  }

  /// Unit directions spread over the sphere of directions, seeded.
  func spreadDirections(_ count: Int, seed: UInt64) -> [Vector3<Double>] {
    var generator = SplitMix64(seed: seed)
    return (0..<count).map { _ in generator.unitVector(Double.self) }
  }

  func testNearest_OneSphere() {
    let spheres = [Sphere<Double>(center: Vector3(1, 2, -10), radius: 3)]
    let eye = Vector3<Double>(0, 0, 0)
    let toward = (0..<50).map { i in
      Vector3<Double>(1 + Double(i - 25) * 0.15, 2, -10).normalized()
    }
    checkAllKernels(
      spheres, eye: eye, directions: toward + spreadDirections(50, seed: 1),
      "one sphere")
    let fixture = Fixture<StableKernel<Double>>(spheres, eye: eye)
    XCTAssertEqual(fixture.hierarchy.nodes.count, 1, "a single leaf")
    XCTAssertEqual(fixture.hierarchy.depth, 0)
  }

  func testNearest_NoSpheres() {
    let fixture = Fixture<StableKernel<Float>>([], eye: .zero)
    XCTAssertTrue(fixture.hierarchy.nodes.isEmpty)
    XCTAssertNil(fixture.nearest(fixture.ray(Vector3(0, 0, -1))))
  }

  /// Every centre the same, radii differing (so the nearest sphere is the
  /// largest): nothing for binning to separate but last-bit differences
  /// in the boxes' midpoints, and median splits otherwise. Leaves must
  /// still hold at most four and the tree stay shallow.
  func testNearest_AllSpheresAtOneCentre() {
    let center = Vector3<Double>(3, -1, -20)
    let spheres = (0..<1000).map { index in
      Sphere(center: center, radius: 0.5 + Double((index * 37) % 1000) * 1e-3)
    }
    let toward = (0..<60).map { i in
      (center + Vector3(Double(i % 10) * 0.2 - 1, Double(i / 10) * 0.3 - 1, 0))
        .normalized()
    }
    checkAllKernels(
      spheres, eye: .zero, directions: toward + spreadDirections(40, seed: 2),
      "one centre")
    // Centroids are the boxes' midpoints, which differ in the last bit
    // with the radius, so SAH gets some splits; all the same, the tree
    // stays about as shallow as halving (⌈log₂(1000/4)⌉ = 8 levels).
    for depth in [
      Fixture<StableKernel<Float>>(spheres, eye: .zero).hierarchy.depth,
      Fixture<NaiveKernel<Double>>(spheres, eye: .zero).hierarchy.depth,
    ] {
      XCTAssertLessThanOrEqual(depth, 12)
    }
    // Exactly equal centres and radii: median splits only, exactly halving.
    let copies = [Sphere<Double>](
      repeating: Sphere(center: center, radius: 1), count: 1000)
    XCTAssertEqual(
      Fixture<StableKernel<Float>>(copies, eye: .zero).hierarchy.depth, 8)
  }

  /// Identical spheres give identical roots: of equal t, both the flat
  /// loop and the hierarchy keep the sphere first in the scene's order.
  func testNearest_TiesResolveToFirstInSceneOrder() {
    var spheres: [Sphere<Double>] = []
    for copy in 0..<40 {
      spheres.append(Sphere(center: Vector3(0, 0, -10), radius: 2))
      spheres.append(
        Sphere(center: Vector3(Double(copy) - 20, 5, -30), radius: 1))
      spheres.append(Sphere(center: Vector3(4, -3, -15), radius: 1.5))
    }
    let toward = [
      Vector3<Double>(0, 0, -1), Vector3(0.05, 0.02, -1).normalized(),
      Vector3(4, -3, -15).normalized(), Vector3(4.3, -3.2, -15).normalized(),
      Vector3(-5, 5, -30).normalized(),
    ]
    checkAllKernels(spheres, eye: .zero, directions: toward, "duplicates")
    // And explicitly: the first copy, index 0, not any other.
    let fixture = Fixture<StableKernel<Double>>(spheres, eye: .zero)
    let hit = fixture.nearest(fixture.ray(Vector3(0, 0, -1)))
    XCTAssertEqual(hit?.t, 8)
    XCTAssertEqual(hit?.index, 0)
    let side = fixture.nearest(
      fixture.ray(Vector3<Double>(4, -3, -15).normalized()))
    XCTAssertEqual(side?.index, 2, "the first of the spheres at (4, −3, −15)")
  }

  /// Spheres along the x axis, evenly and then exponentially spaced (which
  /// SAH peels one at a time until the depth limit forces median splits),
  /// seen along the line itself (direction components exactly zero) and
  /// across it.
  func testNearest_SpheresOnALine() {
    let even = (0..<2000).map { index in
      Sphere<Double>(center: Vector3(Double(index), 0, 0), radius: 0.3)
    }
    let along: [Vector3<Double>] = [
      Vector3(1, 0, 0), Vector3(-1, 0, 0), Vector3(1, -0.0, 0),
      Vector3(1, 1e-3, 0).normalized(), Vector3(1, 0, 2e-4).normalized(),
    ]
    for eye in Self.quickCases([
      Vector3<Double>(-5, 0, 0), Vector3(1000.5, 0, 0.1), Vector3(-5, 0.25, 0),
    ]) {
      checkAllKernels(
        even, eye: eye,
        directions: along + spreadDirections(runsLongTests ? 40 : 12, seed: 3),
        "even line, eye \(eye)")
    }
    // Centres 1.05^i: SAH's best split keeps cutting off the far end.
    let exponential = (0..<3000).map { index in
      Sphere<Double>(
        center: Vector3(Double.pow(1.05, Double(index)), 0, 0),
        radius: 0.01 * Double.pow(1.05, Double(index)))
    }
    checkAllKernels(
      exponential, eye: Vector3(-1, 0.001, 0),
      directions: along + spreadDirections(runsLongTests ? 40 : 12, seed: 4),
      "exponential line")
    let fixture = Fixture<StableKernel<Double>>(exponential, eye: .zero)
    XCTAssertLessThan(
      fixture.hierarchy.depth, BoundingVolumeHierarchy<Double>.stackCapacity)
  }

  /// Radii from 10⁻⁶ to 10⁶ in one scene, the eye inside the largest
  /// (rays hit its far side) and next to the smallest.
  func testNearest_HugeAndTinyRadii() {
    var generator = SplitMix64(seed: 0x51E)
    var spheres = [
      Sphere<Double>(center: Vector3(10, -20, 30), radius: 1e6),
      Sphere(center: Vector3(0, 0, -3e-6), radius: 1e-6),
      Sphere(center: Vector3(0, 2e-6, -1e-5), radius: 2e-6),
    ]
    for _ in 0..<200 {
      let center =
        generator.unitVector(Double.self) * generator.logUniform(1e-5, 1e5)
      spheres.append(
        Sphere(
          center: center,
          radius: center.length * generator.logUniform(1e-6, 0.5)))
    }
    var directions = spheres.map { $0.center.normalized() }
    directions += spreadDirections(60, seed: 5)
    directions += [Vector3(0, 0, -1), Vector3(0, 0.2, -1).normalized()]
    checkAllKernels(
      spheres, eye: .zero, directions: directions, "radii 1e-6…1e6")
  }
}
