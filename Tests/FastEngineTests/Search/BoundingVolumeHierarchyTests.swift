import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

final class BoundingVolumeHierarchyTests: XCTestCase {
  // MARK: - Fixture

  /// Spheres stored as `Kernel` stores them, in the scene's order for the
  /// brute-force loop and in leaf order for the hierarchy, as
  /// `CompiledScene` does.
  struct Fixture<Kernel: IntersectionKernel> {
    typealias Scalar = Kernel.Scalar
    let records: [Kernel.SphereRecord]
    let ordered: [Kernel.SphereRecord]
    let hierarchy: BoundingVolumeHierarchy<Scalar>
    /// The same hierarchy four-wide; nil only where it declines.
    let wide: WideHierarchy<Scalar>?
    let origin: Vector3<Scalar>

    init(_ spheres: [Sphere<Double>], eye: Vector3<Double>) {
      records = spheres.map { Kernel.makeSphere($0, eye: eye) }
      origin = Kernel.frameOrigin(eye: eye)
      hierarchy = BoundingVolumeHierarchy(
        spheres: records, kernel: Kernel.self, rayOrigin: origin)
      ordered = hierarchy.order.map { [records] in records[Int($0)] }
      wide = WideHierarchy(hierarchy, rayOrigin: origin)
    }

    func ray(_ direction: Vector3<Scalar>) -> CameraRay<Scalar> {
      CameraRay(origin: origin, direction: direction)
    }

    /// The render loop's flat path: every sphere in the scene's order, each
    /// only having to beat the nearest so far.
    func bruteForce(
      _ ray: CameraRay<Scalar>, before tMax: Scalar = .infinity
    ) -> (t: Scalar, index: Int)? {
      var tBest = tMax
      var best: Int?
      for index in records.indices {
        if let t = Kernel.intersect(records[index], ray, before: tBest) {
          tBest = t
          best = index
        }
      }
      return best.map { (tBest, $0) }
    }

    /// The render loop's answer (the wide hierarchy where it can answer,
    /// else the binary one), its index mapped back to the scene's order.
    func nearest(
      _ ray: CameraRay<Scalar>, before tMax: Scalar = .infinity
    ) -> (t: Scalar, index: Int)? {
      let hit = ordered.withUnsafeBufferPointer {
        hierarchy.nearest(
          ray, before: tMax,
          leaves: SphereLeaves<Kernel>(records: $0, ray: ray), wide: wide)
      }
      return hit.map { ($0.t, Int(hierarchy.order[$0.index])) }
    }

    /// The binary hierarchy's own answer, in the scene's order.
    func binaryNearest(
      _ ray: CameraRay<Scalar>, before tMax: Scalar = .infinity
    ) -> (t: Scalar, index: Int)? {
      let hit = ordered.withUnsafeBufferPointer {
        hierarchy.nearest(ray, before: tMax, records: $0, kernel: Kernel.self)
      }
      return hit.map { ($0.t, Int(hierarchy.order[$0.index])) }
    }

    /// Asserts the hierarchy agrees with brute force exactly: the same t
    /// bit for bit and the same sphere (ties included: both take the
    /// sphere first in the scene's order). Returns the number of hits.
    @discardableResult
    func checkMatches(
      _ directions: [Vector3<Scalar>], before tMax: Scalar = .infinity,
      _ context: @autoclosure () -> String = "",
      file: StaticString = #filePath, line: UInt = #line
    ) -> Int {
      var hits = 0
      var failures = 0
      for direction in directions {
        let ray = ray(direction)
        let want = bruteForce(ray, before: tMax)
        if want != nil { hits += 1 }
        for (name, got) in [
          ("hierarchy", nearest(ray, before: tMax)),
          ("binary hierarchy", binaryNearest(ray, before: tMax)),
        ] {
          guard got?.t != want?.t || got?.index != want?.index else { continue }
          failures += 1
          // A few are enough to diagnose; thousands would bury the seed.
          guard failures <= 3 else { continue }
          XCTFail(
            "\(Kernel.self) \(context()): direction \(direction): \(name) "
              + "\(String(describing: got)), brute force "
              + "\(String(describing: want))",
            file: file, line: line)
        }
      }
      return hits
    }
  }

  // MARK: - Random scenes

  /// A cluster of `count` spheres in a cube of side L (log-uniform from
  /// 10⁻² to 10³, centred up to 10³ from the origin), radii log-uniform
  /// from 10⁻⁵·L to 0.3·L so that small far spheres (where the textbook
  /// kernel's cancellation reports hits outside the sphere) are common, and
  /// the eye up to 50·L away, or inside the cluster.
  func randomScene(
    _ generator: inout SplitMix64, count: Int
  ) -> (spheres: [Sphere<Double>], eye: Vector3<Double>) {
    let size: Double = generator.logUniform(1e-2, 1e3)
    let center =
      generator.unitVector(Double.self) * generator.logUniform(1, 1e3)
    let spheres = (0..<count).map { _ in
      let offset = Vector3<Double>(
        generator.uniform(-0.5...0.5), generator.uniform(-0.5...0.5),
        generator.uniform(-0.5...0.5))
      return Sphere(
        center: center + offset * size,
        radius: generator.logUniform(1e-5 * size, 0.3 * size))
    }
    let away: Double =
      Bool.random(using: &generator) ? generator.logUniform(0.6, 50) : 0.2
    let eye = center + generator.unitVector(Double.self) * (away * size)
    return (spheres, eye)
  }

  /// Directions from the eye: at sphere centres, at their silhouettes
  /// (within a few ulps either side), just past them (by 10⁻²·ε to 10⁻²
  /// of the distance, where the kernels' rounding can still report a hit),
  /// uniformly at random, and with one or two components zeroed (±0).
  func randomDirections<T: RayScalar>(
    _ generator: inout SplitMix64, spheres: [Sphere<Double>],
    eye: Vector3<Double>, count: Int, as _: T.Type
  ) -> [Vector3<T>] {
    (0..<count).compactMap { _ -> Vector3<T>? in
      let sphere = spheres[Int.random(in: spheres.indices, using: &generator)]
      let toCenter = sphere.center - eye
      var direction: Vector3<Double>
      var across = toCenter.cross(generator.unitVector(Double.self))
      guard across.maxMagnitude > 0 else { return nil }
      across = across.normalized()
      switch Int.random(in: 0..<7, using: &generator) {
      case 0:
        direction = toCenter
      case 1, 2:
        // Past the centre at r·(1 ± a few ulps of T): the silhouette,
        // where roots are least accurate.
        let nudge = Double(T.ulpOfOne) * generator.uniform(-4...4)
        direction = toCenter + across * (sphere.radius * (1 + nudge))
      case 3, 4:
        // Just outside: the textbook kernel reports hits up to about
        // 2√ε·distance out, the stable one about ε·distance.
        let gap: Double = generator.logUniform(1e-2 * Double(T.ulpOfOne), 1e-2)
        direction = toCenter + across * (sphere.radius + gap * toCenter.length)
      case 5:
        direction = generator.unitVector(Double.self)
      default:
        direction = toCenter
        let zeros = Int.random(in: 1...2, using: &generator)
        for _ in 0..<zeros {
          let zero: Double = Bool.random(using: &generator) ? 0 : -0.0
          switch Int.random(in: 0..<3, using: &generator) {
          case 0: direction.x = zero
          case 1: direction.y = zero
          default: direction.z = zero
          }
        }
      }
      guard direction.maxMagnitude > 0, direction.isFinite else { return nil }
      let rounded = Vector3<T>(direction.normalized())
      return rounded.maxMagnitude > 0 ? rounded : nil
    }
  }

  func checkRandomScenes<Kernel: IntersectionKernel>(
    _: Kernel.Type, base: UInt64, file: StaticString = #filePath,
    line: UInt = #line
  ) {
    var rays = 0
    var hits = 0
    forEachSeed(40, base: base, file: file, line: line) { generator, seed in
      let count = Int(generator.logUniform(1.0, 400.0))
      let (spheres, eye) = randomScene(&generator, count: count)
      let fixture = Fixture<Kernel>(spheres, eye: eye)
      let directions = randomDirections(
        &generator, spheres: spheres, eye: eye, count: 120,
        as: Kernel.Scalar.self)
      rays += directions.count
      hits += fixture.checkMatches(
        directions, "seed 0x\(String(seed, radix: 16)), \(count) spheres",
        file: file, line: line)
      checkStructure(
        fixture.hierarchy, spheres: fixture.records, kernel: Kernel.self,
        file: file, line: line)
    }
    // Neither all misses nor all hits: both outcomes are compared.
    XCTAssertGreaterThan(
      hits, rays / 4, "\(Kernel.self)", file: file, line: line)
    XCTAssertLessThan(hits, rays, "\(Kernel.self)", file: file, line: line)
  }

  func testNearest_MatchesBruteForce_RandomScenes_Float() {
    checkRandomScenes(StableKernel<Float>.self, base: 0xB5F1)
    checkRandomScenes(NaiveKernel<Float>.self, base: 0xB5F2)
  }

  func testNearest_MatchesBruteForce_RandomScenes_Double() {
    checkRandomScenes(StableKernel<Double>.self, base: 0xB5D1)
    checkRandomScenes(NaiveKernel<Double>.self, base: 0xB5D2)
  }

  /// A finite tMax is honoured as the flat loop honours it: no hit at or
  /// beyond it.
  func checkBefore<Kernel: IntersectionKernel>(_: Kernel.Type, base: UInt64) {
    forEachSeed(20, base: base) { generator, _ in
      let (spheres, eye) = randomScene(&generator, count: 60)
      let fixture = Fixture<Kernel>(spheres, eye: eye)
      let directions = randomDirections(
        &generator, spheres: spheres, eye: eye, count: 60,
        as: Kernel.Scalar.self)
      // A bound at a typical hit distance, so that it cuts some hits off.
      let tMax = Kernel.Scalar((spheres[0].center - eye).length)
      fixture.checkMatches(directions, before: tMax, "before \(tMax)")
    }
  }

  func testNearest_HonoursTMax() {
    checkBefore(StableKernel<Float>.self, base: 0x7A1)
    checkBefore(NaiveKernel<Double>.self, base: 0x7A2)
  }
}
