import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension BoundingVolumeHierarchyTests {
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
}
