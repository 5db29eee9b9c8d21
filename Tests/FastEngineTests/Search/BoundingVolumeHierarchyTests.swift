import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import Numerics
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

  // MARK: - Ray–box test

  /// The slab test on hand-made boxes: faces in the plane of the origin
  /// with the ray parallel to them (the 0·∞ = NaN case), a flat box, a
  /// touched corner, and misses by one ulp.
  func checkSlab<T: RayScalar>(_: T.Type) {
    typealias BVH = BoundingVolumeHierarchy<T>
    func box(_ lower: Vector3<T>, _ upper: Vector3<T>) -> BVH.Node {
      BVH.Node(lower: lower, upper: upper, index: 0, count: 1)
    }
    func entry(
      _ node: BVH.Node, from origin: Vector3<T>, _ direction: Vector3<T>,
      before bound: T = .infinity
    ) -> T? {
      BVH.Slab(CameraRay(origin: origin, direction: direction))
        .entry(node, before: bound)
    }
    let unit = box(Vector3(0, 0, 5), Vector3(1, 1, 6))
    let up = Vector3<T>(0, 0, 1)
    // The origin in the plane of each face the ray runs parallel to.
    for face in [
      Vector3<T>(0, 0.5, 0), Vector3(1, 0.5, 0), Vector3(0.5, 0, 0),
      Vector3(0.5, 1, 0), Vector3(0, 1, 0), Vector3(1, 0, 0),
    ] {
      XCTAssertEqual(entry(unit, from: face, up), 5, "\(T.self) from \(face)")
      XCTAssertEqual(
        entry(unit, from: face + Vector3(0, 0, 12), -up), 6,
        "\(T.self) from \(face) downwards")
    }
    let across = box(Vector3(5, 0, 0), Vector3(6, 1, 1))
    XCTAssertEqual(
      entry(across, from: Vector3(0, 1, 0), Vector3(1, 0, 0)), 5, "\(T.self)")
    XCTAssertEqual(
      entry(across, from: Vector3(0, 0, 1), Vector3(1, 0, 0)), 5, "\(T.self)")
    XCTAssertEqual(
      entry(unit, from: Vector3(-0.0, 0.5, 0), Vector3(-0.0, 0, 1)), 5,
      "\(T.self): −0 direction, −∞ inverse")
    XCTAssertNil(
      entry(unit, from: Vector3(T(0).nextDown, 0.5, 0), up),
      "\(T.self): one ulp outside the x slab")
    XCTAssertNil(
      entry(unit, from: Vector3(0.5, T(1).nextUp, 0), up),
      "\(T.self): one ulp outside the y slab")
    // A flat box, the ray in its plane.
    let flat = box(Vector3(2, 0, 5), Vector3(2, 1, 6))
    XCTAssertEqual(entry(flat, from: Vector3(2, 0.5, 0), up), 5, "\(T.self)")
    // Touching a corner: entry and exit coincide.
    let corner = box(Vector3(1, 1, -1), Vector3(2, 2, 1))
    XCTAssertEqual(
      entry(corner, from: Vector3(0, 2, 0), Vector3(1, -1, 0)), 1, "\(T.self)")
    // The origin inside: entry clamped to 0.
    XCTAssertEqual(
      entry(unit, from: Vector3(0.5, 0.5, 5.5), Vector3(0, 0, -1)), 0)
    // Behind the origin, and beyond the bound.
    XCTAssertNil(entry(unit, from: Vector3(0.5, 0.5, 7), up), "\(T.self)")
    XCTAssertNil(
      entry(unit, from: Vector3(0.5, 0.5, 0), up, before: T(5).nextDown * 0.99),
      "\(T.self)")
    XCTAssertEqual(
      entry(unit, from: Vector3(0.5, 0.5, 0), up, before: 5), 5,
      "\(T.self): entered exactly at the bound, kept for ties")
  }

  /// A ray that touches a box only at a corner, where it leaves one slab
  /// exactly as it enters another: with 1/d rounded the two distances
  /// can come out in either order, and the 1 + 2γ₃ on the exit keeps the
  /// box.
  func checkSlabCorner<T: RayScalar>(_: T.Type) {
    typealias BVH = BoundingVolumeHierarchy<T>
    var generator = SplitMix64(seed: 0xC0C)
    var rejected = 0
    for _ in 0..<2000 {
      let direction = Vector3<T>(
        generator.uniform(0.1...1), generator.uniform(0.1...1),
        generator.uniform(0.1...1))
      // 4·d is exact, so the corner is exactly on the ray at t = 4; the box
      // lies beyond it in x and z but below it in y.
      let corner = direction * 4
      let node = BVH.Node(
        lower: Vector3(corner.x, corner.y - 1, corner.z),
        upper: Vector3(corner.x + 1, corner.y, corner.z + 1), index: 0,
        count: 1)
      let slab = BVH.Slab(CameraRay(origin: .zero, direction: direction))
      if slab.entry(node, before: .infinity) == nil { rejected += 1 }
    }
    XCTAssertEqual(rejected, 0, "\(T.self): corners touched but rejected")
  }

  func testSlab_TouchingCornerWithRoundedInverse_Float() {
    checkSlabCorner(Float.self)
  }
  func testSlab_TouchingCornerWithRoundedInverse_Double() {
    checkSlabCorner(Double.self)
  }

  /// Rays with a zero x component passing just outside spheres along x, so
  /// that only the boxes' x faces can cull them: the faces must sit beyond
  /// every hit the kernel's rounding reports (about 2√ε·distance out for
  /// the textbook kernel, ε·distance for the stable one).
  func checkGrazingAlongAxis<Kernel: IntersectionKernel>(
    _: Kernel.Type, base: UInt64
  ) {
    var hits = 0
    forEachSeed(20, base: base) { generator, _ in
      var spheres: [Sphere<Double>] = []
      var directions: [Vector3<Kernel.Scalar>] = []
      for _ in 0..<40 {
        let distance: Double = generator.logUniform(1, 1e4)
        let radius = distance * generator.logUniform(1e-6, 0.2)
        let gap =
          distance
          * generator.logUniform(1e-2 * Double(Kernel.Scalar.ulpOfOne), 1e-2)
        let angle = Double.random(in: -1.2...1.2, using: &generator)
        let side: Double = generator.sign()
        spheres.append(
          Sphere(
            center: Vector3(
              side * (radius + gap), distance * Double.sin(angle),
              -distance * Double.cos(angle)),
            radius: radius))
        directions.append(
          Vector3(
            0, Kernel.Scalar(Double.sin(angle)),
            Kernel.Scalar(-Double.cos(angle))))
      }
      hits += Fixture<Kernel>(spheres, eye: .zero).checkMatches(
        directions, "grazing x")
    }
    // Every ray misses every sphere in exact arithmetic, but the textbook
    // kernel's rounding reports hits on many (in these seeds about half in
    // Float, a fifth in Double): the boxes must be wide enough to keep
    // them.
    if Kernel.self == NaiveKernel<Kernel.Scalar>.self {
      XCTAssertGreaterThan(hits, 20 * 40 / 10, "\(Kernel.self)")
    }
  }

  func testNearest_RaysGrazingBoxFaces() {
    checkGrazingAlongAxis(StableKernel<Float>.self, base: 0x6F1)
    checkGrazingAlongAxis(StableKernel<Double>.self, base: 0x6D1)
    checkGrazingAlongAxis(NaiveKernel<Float>.self, base: 0x6F2)
    checkGrazingAlongAxis(NaiveKernel<Double>.self, base: 0x6D2)
  }

  func testSlab_ZeroDirectionComponentsAndTouchingBoxes_Float() {
    checkSlab(Float.self)
  }
  func testSlab_ZeroDirectionComponentsAndTouchingBoxes_Double() {
    checkSlab(Double.self)
  }

  // MARK: - Structure

  /// The layout and containment invariants, for any hierarchy over
  /// `spheres` (in the scene's order).
  func checkStructure<Kernel: IntersectionKernel>(
    _ hierarchy: BoundingVolumeHierarchy<Kernel.Scalar>,
    spheres: [Kernel.SphereRecord], kernel: Kernel.Type,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    typealias BVH = BoundingVolumeHierarchy<Kernel.Scalar>
    let nodes = hierarchy.nodes
    XCTAssertEqual(
      hierarchy.order.sorted(), (0..<Int32(spheres.count)).map { $0 },
      "order is a permutation", file: file, line: line)
    guard !nodes.isEmpty else {
      XCTAssertTrue(spheres.isEmpty, file: file, line: line)
      return
    }
    // Walk depth first, left child first: children must be adjacent and
    // allocated in that order, and the leaves must cover the spheres in
    // order, each exactly once.
    var nextPair = 1
    var nextSphere = 0
    var deepest = 0
    var problems: [String] = []
    var stack = [(node: 0, depth: 0)]
    while let (index, depth) = stack.popLast() {
      let node = nodes[index]
      deepest = max(deepest, depth)
      guard node.lower.x <= node.upper.x, node.lower.y <= node.upper.y,
        node.lower.z <= node.upper.z
      else {
        problems.append("node \(index) has an inverted box")
        continue
      }
      if node.isLeaf {
        if node.count > BVH.maximumLeafSize {
          problems.append("leaf \(index) holds \(node.count)")
        }
        if Int(node.index) != nextSphere {
          problems.append(
            "leaf \(index) starts at \(node.index), not \(nextSphere)")
        }
        for position in Int(node.index)..<Int(node.index + node.count) {
          let (center, radius) = Kernel.centerAndRadius(
            spheres[Int(hierarchy.order[position])])
          // The exact sphere, at least, lies inside its leaf's box.
          let lower = center - Vector3(radius, radius, radius)
          let upper = center + Vector3(radius, radius, radius)
          if !(contains(node, lower: lower, upper: upper)) {
            problems.append("leaf \(index) does not hold sphere at \(position)")
          }
        }
        nextSphere = Int(node.index + node.count)
      } else {
        let first = Int(node.index)
        if first != nextPair || first + 1 >= nodes.count {
          problems.append(
            "node \(index)'s children at \(first), not \(nextPair)")
          continue
        }
        if !(0...2).contains(node.axis) {
          problems.append("node \(index) split on axis \(node.axis)")
        }
        nextPair += 2
        for child in [first, first + 1] {
          let box = nodes[child]
          if !contains(node, lower: box.lower, upper: box.upper) {
            problems.append("node \(index) does not hold child \(child)")
          }
        }
        stack.append((first + 1, depth + 1))
        stack.append((first, depth + 1))
      }
    }
    XCTAssertEqual(
      nextPair, nodes.count, "every node reached", file: file, line: line)
    XCTAssertEqual(
      nextSphere, spheres.count, "every sphere in a leaf", file: file,
      line: line)
    XCTAssertEqual(deepest, hierarchy.depth, file: file, line: line)
    XCTAssertLessThan(deepest, BVH.stackCapacity, file: file, line: line)
    XCTAssertTrue(
      problems.isEmpty, "\(problems.prefix(5))", file: file, line: line)
  }

  /// No part of the box [lower, upper] lies outside the node's; written
  /// with negations so that the NaN bounds of a sphere whose centre
  /// overflowed (∞ − ∞) are vacuously held.
  func contains<T: RayScalar>(
    _ node: BoundingVolumeHierarchy<T>.Node, lower: Vector3<T>,
    upper: Vector3<T>
  ) -> Bool {
    !(lower.x < node.lower.x || lower.y < node.lower.y
      || lower.z < node.lower.z || upper.x > node.upper.x
      || upper.y > node.upper.y || upper.z > node.upper.z)
  }

  /// The same input gives the same tree, whether the two halves are built
  /// on two threads or one after the other.
  func testBuild_IsDeterministic_ConcurrentOrNot() {
    var generator = SplitMix64(seed: 0xDE7)
    let boxes = (0..<6000).map {
      _ -> (lower: Vector3<Float>, upper: Vector3<Float>) in
      let center = Vector3<Float>(
        generator.unitVector(Double.self) * generator.logUniform(1, 100))
      let radius: Float = generator.logUniform(0.01, 2)
      return BoundingVolumeHierarchy<Float>.box(
        center: center, radius: radius, rayOrigin: .zero,
        model: .cancellationFree)
    }
    let sequential = BoundingVolumeHierarchy<Float>(
      boxes: boxes, concurrentFrom: .max)
    let concurrent = BoundingVolumeHierarchy<Float>(
      boxes: boxes, concurrentFrom: 1000)
    let again = BoundingVolumeHierarchy<Float>(
      boxes: boxes, concurrentFrom: 1000)
    XCTAssertEqual(sequential.nodes, concurrent.nodes)
    XCTAssertEqual(sequential.order, concurrent.order)
    XCTAssertEqual(sequential.depth, concurrent.depth)
    XCTAssertEqual(concurrent.nodes, again.nodes)
    XCTAssertEqual(concurrent.order, again.order)
  }

  /// The same tree from 1, 2, 3, 7 and 16 threads: the primitives, the
  /// root's bounds and bins in one part per thread (here of at least 500
  /// boxes, so 16 threads make 16 parts), merged in order.
  func testBuild_AnyThreadCount_SameTree() {
    var generator = SplitMix64(seed: 0x7EAD5)
    let boxes = (0..<20_000).map {
      _ -> (lower: Vector3<Double>, upper: Vector3<Double>) in
      let center =
        generator.unitVector(Double.self) * generator.logUniform(1, 100)
      // Some boxes share their bounds, so the merge order of equal values
      // (and of ±0) shows.
      let radius: Double =
        generator.next() % 8 == 0 ? 1 : generator.logUniform(0.01, 2)
      return BoundingVolumeHierarchy<Double>.box(
        center: Vector3(
          center.x.rounded(), center.y.rounded(), center.z.rounded()),
        radius: radius, rayOrigin: .zero, model: .cancellationFree)
    }
    typealias BVH = BoundingVolumeHierarchy<Double>
    let one = BVH(boxes: boxes, concurrentFrom: 1000, threads: 1)
    XCTAssertEqual(
      BVH.parts(boxes.count, concurrentFrom: 1000, threads: 16), 16)
    for threads in runsLongTests ? [2, 3, 7, 16] : [3, 16] {
      let many = BVH(boxes: boxes, concurrentFrom: 1000, threads: threads)
      XCTAssertEqual(many.nodes, one.nodes, "\(threads) threads: nodes")
      XCTAssertEqual(many.order, one.order, "\(threads) threads: order")
      XCTAssertEqual(many.depth, one.depth, "\(threads) threads: depth")
    }
  }

  /// Spheres give the same tree whether their boxes, the root's bounds
  /// and bins and the two subtrees are computed on two threads or one, and
  /// the same as their boxes given directly.
  func testBuildFromSpheres_IsDeterministic_ConcurrentOrNot() {
    typealias Kernel = StableKernel<Double>
    var generator = SplitMix64(seed: 0x5FE)
    let spheres = (0..<5000).map { index -> Sphere<Double> in
      let center =
        generator.unitVector(Double.self) * generator.logUniform(1, 100)
      return Sphere(
        center: center, radius: generator.logUniform(0.01, 2), materialIndex: 0)
    }
    let eye = Vector3<Double>(0, 0, 150)
    let records = spheres.map { Kernel.makeSphere($0, eye: eye) }
    let origin = Kernel.frameOrigin(eye: eye)
    typealias BVH = BoundingVolumeHierarchy<Double>
    let sequential = BVH(
      spheres: records, kernel: Kernel.self, rayOrigin: origin,
      concurrentFrom: .max)
    let concurrent = BVH(
      spheres: records, kernel: Kernel.self, rayOrigin: origin,
      concurrentFrom: 100)
    let boxes = records.map { record in
      let (center, radius) = Kernel.centerAndRadius(record)
      return BVH.box(
        center: center, radius: radius, rayOrigin: origin,
        model: .cancellationFree)
    }
    let fromBoxes = BVH(boxes: boxes, concurrentFrom: .max)
    XCTAssertEqual(sequential.nodes, concurrent.nodes)
    XCTAssertEqual(sequential.order, concurrent.order)
    XCTAssertEqual(sequential.depth, concurrent.depth)
    XCTAssertEqual(sequential.nodes, fromBoxes.nodes)
    XCTAssertEqual(sequential.order, fromBoxes.order)
  }

  /// Binning a range as four blocks gives the bins of one pass bit for bit,
  /// signed zeros included, for every length around the blocks' edges.
  func testFill_FourBlocksGiveTheBinsOfOnePass() {
    typealias BVH = BoundingVolumeHierarchy<Float>
    var generator = SplitMix64(seed: 0xF11)
    // Coordinates from a few values, zeros of both signs among them, so
    // that bins see many equal values.
    let values: [Float] = [-0.0, 0.0, 1, -1, 2.5, 0.0, -0.0]
    func pick() -> Float {
      values[Int(generator.next() % UInt64(values.count))]
    }
    for count in [1, 2, 63, 64, 65, 66, 67, 200, 1001] {
      var primitives = (0..<count).map { index -> BVH.Primitive in
        let lower = Vector3(pick(), pick(), pick())
        let upper = Vector3(
          Swift.max(lower.x, pick()), Swift.max(lower.y, pick()),
          Swift.max(lower.z, pick()))
        return BVH.Primitive(
          lower: lower, upper: upper, index: Int32(index))
      }
      var centroids = BVH.Bounds()
      for primitive in primitives {
        centroids.include(lower: primitive.centroid, upper: primitive.centroid)
      }
      guard let binning = BVH.Binning(centroids, primitives: count) else {
        continue
      }
      var onePass = [BVH.Bin](repeating: BVH.Bin(), count: binning.count)
      var blocks = [BVH.Bin](repeating: BVH.Bin(), count: 4 * binning.count)
      primitives.withUnsafeMutableBufferPointer { primitives in
        onePass.withUnsafeMutableBufferPointer {
          BVH.Builder.fill($0, primitives, primitives.indices, binning)
        }
        blocks.withUnsafeMutableBufferPointer {
          BVH.Builder.fill($0, primitives, primitives.indices, binning)
        }
      }
      func bits(_ bounds: BVH.Bounds) -> [UInt32] {
        [
          bounds.lower.x, bounds.lower.y, bounds.lower.z, bounds.upper.x,
          bounds.upper.y, bounds.upper.z,
        ].map(\.bitPattern)
      }
      for bin in 0..<binning.count {
        XCTAssertEqual(onePass[bin].count, blocks[bin].count, "\(count) \(bin)")
        XCTAssertEqual(
          bits(onePass[bin].summary.bounds), bits(blocks[bin].summary.bounds),
          "\(count) \(bin)")
        XCTAssertEqual(
          bits(onePass[bin].summary.centroids),
          bits(blocks[bin].summary.centroids), "\(count) \(bin)")
      }
    }
  }

  /// The partition leaves the primitives as a two-pointer scan does, for
  /// every boundary between bins and ranges of many lengths.
  func testPartition_MatchesTwoPointerScan() {
    typealias BVH = BoundingVolumeHierarchy<Double>
    var generator = SplitMix64(seed: 0x9A27)
    for count in [2, 3, 5, 17, 100, 1000] {
      let primitives = (0..<count).map { index -> BVH.Primitive in
        let center = Vector3<Double>(
          generator.uniform(-10...10), generator.uniform(-10...10),
          generator.uniform(-10...10))
        let box = Vector3<Double>(0.5, 0.5, 0.5)
        return BVH.Primitive(
          lower: center - box, upper: center + box, index: Int32(index))
      }
      var centroids = BVH.Bounds()
      for primitive in primitives {
        centroids.include(lower: primitive.centroid, upper: primitive.centroid)
      }
      guard let binning = BVH.Binning(centroids, primitives: count) else {
        return XCTFail("\(count) random centroids cannot be binned")
      }
      var builder = BVH.Builder()
      builder.bins.withUnsafeMutableBufferPointer { bins in
        var mutable = primitives
        mutable.withUnsafeMutableBufferPointer {
          BVH.Builder.fill(bins, $0, $0.indices, binning)
        }
      }
      for firstRight in 1..<binning.count {
        func isLeft(_ primitive: BVH.Primitive) -> Bool {
          binning.bin(primitive.centroid) < firstRight
        }
        var expected = primitives
        var low = 0
        var high = count - 1
        while true {
          while low <= high && isLeft(expected[low]) { low += 1 }
          while low < high && !isLeft(expected[high]) { high -= 1 }
          guard low < high else { break }
          expected.swapAt(low, high)
          low += 1
          high -= 1
        }
        var actual = primitives
        let middle = actual.withUnsafeMutableBufferPointer {
          builder.partition(
            $0, $0.indices, axis: binning.axis, origin: binning.origin,
            scale: binning.scale, bins: binning.count, firstRight: firstRight)
        }
        XCTAssertEqual(middle, low, "\(count) \(firstRight)")
        XCTAssertEqual(
          actual.map(\.index), expected.map(\.index), "\(count) \(firstRight)")
      }
    }
  }

  /// Every box holds the sphere with room for the kernel's rounding: more
  /// room for the textbook kernel, whose reach grows with √ε·distance.
  func testBox_HoldsSphereWithRoomForRounding() {
    typealias BVH = BoundingVolumeHierarchy<Float>
    let center = Vector3<Float>(0, 0, -1000)
    let stable = BVH.box(
      center: center, radius: 0.01, rayOrigin: .zero, model: .cancellationFree)
    let textbook = BVH.box(
      center: center, radius: 0.01, rayOrigin: .zero, model: .textbook)
    // The stable reach is r + γ₃₂·(distance + r): 0.01 + 0.002 here.
    XCTAssertGreaterThan(stable.upper.x, 0.011)
    XCTAssertLessThan(stable.upper.x, 0.013)
    // The textbook reach is about √γ₆₄·distance ≈ 2 here, two hundred
    // radii: b² − 4ac carries an error of order γ·|d|²·distance², which is
    // 4a(r² − ℓ²) for ℓ, the ray's distance from the centre, of order
    // √γ·distance.
    XCTAssertGreaterThan(textbook.upper.x, 1.5)
    XCTAssertLessThan(textbook.upper.x, 2.5)
    // A NaN sphere never hits; its box is everything, not NaN.
    let nan = BVH.box(
      center: Vector3(.nan, 0, 0), radius: 1, rayOrigin: .zero,
      model: .cancellationFree)
    XCTAssertEqual(nan.lower.y, -.infinity)
    XCTAssertEqual(nan.upper.x, .infinity)
  }

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
