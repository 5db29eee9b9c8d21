import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Pipeline
@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Rendering a scene with its lengths rescaled by a power of two
/// (`LengthScale`) changes nothing but the range it works in: t scales
/// exactly, normals and hits are the same bits.
final class LengthScaleTests: XCTestCase {
  /// A sphere, a plane, a triangle and an ellipsoid, every length times
  /// `f` (a power of two, so the scene's values are exact multiples).
  func scene(_ f: Double) throws -> Scene {
    let camera = try XCTUnwrap(
      PerspectiveCamera(
        center: Vector3(0.3, 0.2, 3) * f, direction: Vector3(-0.1, -0.1, -1),
        up: Vector3(0, 1, 0), angle: 50))
    let stretch = try XCTUnwrap(
      Transform(
        matrix: .translation(Vector3(0.8, 0.6, 0.5) * f)
          * .scale(Vector3(0.2, 0.4, 0.2) * f),
        object: .sphere(Sphere(center: .zero, radius: 1))))
    return Scene(
      camera: camera,
      root: Group([
        .sphere(Sphere(center: .zero, radius: f)),
        .plane(Plane(normal: Vector3(0, 1, 0), offset: -f)),
        .triangle(
          Triangle(
            Vector3(-1.2, -0.9, 0.4) * f, Vector3(-0.4, -0.9, 0.6) * f,
            Vector3(-0.8, 0.1, 0.5) * f)),
        .transform(stretch),
      ]))
  }

  func depthsAndNormals(
    _ scene: Scene, _ precision: Precision
  ) -> (depth: [Double], normals: [Vector3<Double>]) {
    let (buffers, _) = AccuracyRender.render(
      scene, width: 48, height: 40, precision: precision, method: .stable,
      runs: 0)
    switch buffers {
    case .float(let b):
      return (b.depth.map(Double.init), b.normals.map { Vector3($0) })
    case .double(let b): return (b.depth, b.normals)
    }
  }

  func checkPowerOfTwoScales(_ precision: Precision, _ exponents: [Int])
    throws
  {
    let unit = depthsAndNormals(try scene(1), precision)
    XCTAssertGreaterThan(unit.depth.filter(\.isFinite).count, 1000)
    for exponent in exponents {
      let f = LengthScale.factor(exponent)
      let scaled = depthsAndNormals(try scene(f), precision)
      for pixel in unit.depth.indices {
        XCTAssertEqual(
          scaled.depth[pixel], unit.depth[pixel] * f,
          "2^\(exponent) \(precision): t at pixel \(pixel)")
        XCTAssertEqual(
          scaled.normals[pixel], unit.normals[pixel],
          "2^\(exponent) \(precision): normal at pixel \(pixel)")
      }
    }
  }

  func testRender_PowerOfTwoScalesGiveTheSameImage_Float() throws {
    try checkPowerOfTwoScales(.float, [-100, -70, -40, 40, 70, 100])
  }

  func testRender_PowerOfTwoScalesGiveTheSameImage_Double() throws {
    try checkPowerOfTwoScales(.double, [-1000, -600, -300, 300, 600, 1000])
  }

  func testExponent_ZeroWithinTheComfortableRange() {
    var all = Primitives<Double>()
    all.spheres = [Sphere(center: Vector3(1e9, 0, 0), radius: 1e-6)]
    XCTAssertEqual(LengthScale.exponent(all, eye: .zero, as: Float.self), 0)
    all.spheres = [Sphere(center: .zero, radius: 1e25)]
    XCTAssertEqual(LengthScale.exponent(all, eye: .zero, as: Float.self), 83)
    XCTAssertEqual(LengthScale.exponent(all, eye: .zero, as: Double.self), 0)
    all.spheres = [Sphere(center: .zero, radius: 1e-200)]
    XCTAssertEqual(
      LengthScale.exponent(all, eye: .zero, as: Double.self), -665)
  }

  /// A sphere whose radius squared leaves the precision at the scale of
  /// its distance from the eye is named; the same sphere at a scale it can
  /// hold is not.
  func testProblem_SphereTooSmallBesideTheScene() throws {
    let camera = try XCTUnwrap(
      PerspectiveCamera(
        center: Vector3(0, 0, 3), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 45))
    func scene(_ radius: Double) -> Scene {
      Scene(
        camera: camera,
        root: Group([.sphere(Sphere(center: .zero, radius: radius))]))
    }
    XCTAssertEqual(
      LengthScale.problem(scene(1e-25), precision: .float),
      "a sphere of radius 1e-25 (centre 0.0 0.0 0.0) is too small beside "
        + "its distance from the eye (3.0) for float: with that length "
        + "scaled to about 1, its radius squared is below float's normal "
        + "range")
    XCTAssertNil(LengthScale.problem(scene(1e-25), precision: .double))
    XCTAssertNil(LengthScale.problem(scene(1e-15), precision: .float))
    XCTAssertNotNil(LengthScale.problem(scene(1e-160), precision: .double))
    // The unit-sphere scene scaled by 1e-25: nothing too small.
    var small = scene(1e-25)
    small.camera.center = Vector3(0, 0, 3e-25)
    XCTAssertNil(LengthScale.problem(small, precision: .float))
  }

  /// A triangle or ellipsoid too small beside its own distance from the
  /// eye for the precision's squares is named, as a sphere is: one of
  /// 1e-25 three units away in Float. One that only the scene's common
  /// scale cannot hold (a speck of 1e-20 by the eye beside a sphere 1e21
  /// away; Float's squares hold 2^±126) is not: it is traced at its own
  /// scale (`LengthScale.layers`, which puts it in a layer of its own).
  func testProblem_TriangleAndEllipsoidTooSmallBesideTheScene() throws {
    let camera = try XCTUnwrap(
      PerspectiveCamera(
        center: .zero, direction: Vector3(0, 0, -1), up: Vector3(0, 1, 0),
        angle: 45))
    func triangle(_ size: Double, at z: Double) -> SceneObject<Double> {
      .triangle(
        Triangle(
          Vector3(-size, -size, z), Vector3(size, -size, z),
          Vector3(0, size, z), materialIndex: 0))
    }
    func ellipsoid(_ size: Double, at z: Double) throws -> SceneObject<Double> {
      .transform(
        try XCTUnwrap(
          Transform(
            matrix: .translation(Vector3(0, 0, z))
              * .scale(Vector3(size, 2 * size, size)),
            object: .sphere(Sphere(center: .zero, radius: 1)))))
    }
    let far = SceneObject<Double>.sphere(
      Sphere(center: Vector3(0, 0, -3e21), radius: 1e20))
    func scene(_ objects: SceneObject<Double>...) -> Scene {
      Scene(camera: camera, root: Group(objects))
    }
    XCTAssertEqual(
      LengthScale.problem(
        scene(far, triangle(1e-25, at: -3)), precision: .float),
      "a triangle (vertices -1e-25 -1e-25 -3.0, 1e-25 -1e-25 -3.0, 0.0 "
        + "1e-25 -3.0) is too small beside its distance from the eye (up to "
        + "3.0) for float: with that length scaled to about 1, its longest "
        + "edge (2.2360679774997897e-25) squared is below float's normal "
        + "range")
    XCTAssertNil(
      LengthScale.problem(
        scene(triangle(1e-25, at: -3)), precision: .double))
    XCTAssertNil(
      LengthScale.problem(
        scene(triangle(1e-15, at: -3)), precision: .float))
    XCTAssertNotNil(
      LengthScale.problem(
        scene(try ellipsoid(1e-25, at: -3)), precision: .float))
    XCTAssertNil(
      LengthScale.problem(
        scene(try ellipsoid(1e-15, at: -3)), precision: .float))
    // Specks the common scale cannot hold: drawn, each in a layer.
    let specks = scene(
      triangle(1e-20, at: -3e-20), try ellipsoid(1e-20, at: -3e-20), far)
    XCTAssertNil(LengthScale.problem(specks, precision: .float))
    let split = LengthScale.layers(
      specks.root.flattened(), eye: .zero, as: Float.self)
    XCTAssertEqual(split.main.spheres.count, 1)
    XCTAssertEqual(split.main.triangles.count, 0)
    XCTAssertEqual(split.others.count, 1)
    XCTAssertEqual(split.others.first?.primitives.triangles.count, 1)
    XCTAssertEqual(split.others.first?.primitives.transformedSpheres.count, 1)
    XCTAssertEqual(
      LengthScale.layers(specks.root.flattened(), eye: .zero, as: Double.self)
        .others.count, 0, "Double holds both at one scale")
  }

  // MARK: - The searches at extreme scales

  /// 300 spheres in a 10-unit box (seeded), every length times `f`.
  func manySpheres(_ f: Double, seed: UInt64) throws -> Scene {
    var generator = SplitMix64(seed: seed)
    var objects: [SceneObject<Double>] = []
    for _ in 0..<300 {
      let center = Vector3(
        Double.random(in: -5...5, using: &generator),
        Double.random(in: -5...5, using: &generator),
        Double.random(in: -5...5, using: &generator))
      objects.append(
        .sphere(
          Sphere(
            center: center * f,
            radius: Double.random(in: 0.05...0.6, using: &generator) * f)))
    }
    let camera = try XCTUnwrap(
      PerspectiveCamera(
        center: Vector3(0, 0, 14) * f, direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 50))
    return Scene(camera: camera, root: Group(objects))
  }

  /// Every sphere search (each sphere, culled per tile, BVH, screen tiles)
  /// gives the scale-1 image at 2^±100 in Float and 2^±1000 in Double:
  /// the records they search are the rescaled ones.
  func testSearches_PowerOfTwoScales() throws {
    let settings = RenderSettings(
      width: 40, height: 32, outputs: [.depth, .normals])
    let searches: [Renderer.SphereSearch] = [
      .culledPerTile, .hierarchy, .screenTiles,
    ]
    func render<K: IntersectionKernel>(
      _: K.Type, _ scene: Scene, _ search: Renderer.SphereSearch
    ) -> RenderBuffers<K.Scalar> {
      let compiled = CompiledScene<K>(
        scene, hierarchyThreshold: search == .hierarchy ? 0 : .max,
        projectionThreshold: search == .screenTiles ? 0 : .max)
      let rendered = Renderer.renderReportingSearch(
        compiled, settings: settings, overlapLimit: .max)
      XCTAssertEqual(rendered.search, search)
      return rendered.buffers
    }
    func check<K: IntersectionKernel>(_ kernel: K.Type, _ exponents: [Int])
      throws
    {
      let seed: UInt64 = 13
      let unit = try manySpheres(1, seed: seed)
      for search in searches {
        let expected = render(kernel, unit, search)
        XCTAssertGreaterThan(expected.depth.filter(\.isFinite).count, 300)
        for exponent in exponents {
          let f = LengthScale.factor(exponent)
          let scaled = render(
            kernel, try manySpheres(f, seed: seed), search)
          let scale = K.Scalar(f)
          XCTAssertEqual(
            scaled.depth, expected.depth.map { $0 * scale },
            "seed \(seed), 2^\(exponent), \(search): depth")
          XCTAssertEqual(
            scaled.normals, expected.normals,
            "seed \(seed), 2^\(exponent), \(search): normals")
        }
      }
    }
    try check(StableKernel<Float>.self, [-100, 100])
    try check(StableKernel<Double>.self, [-1000, 1000])
  }

  // MARK: - Watertight meshes at every scale

  /// The stiff suite's closed icosphere scaled by `s`, seen from inside
  /// (every ray must leave through some triangle) or from 3s outside.
  func icosphere(_ s: Double, inside: Bool, _ precision: Precision) throws
    -> Scene
  {
    let mesh = ProjectFiles.stiffFolder + "/icosphere.obj"
    let eye = inside ? "\(0.1 * s) 0 0" : "0 0 \(3 * s)"
    let text = """
      PerspectiveCamera { center \(eye) direction 0 0 -1 up 0 1 0 \
      angle 60 }
      Group { numObjects 1 Transform { UniformScale \(s) \
      TriangleMesh { obj_file \(mesh) } } }
      """
    return try SceneParser.parse(
      text, file: "icosphere.txt",
      options: SceneOptions(
        style: .course, precision: precision.numberRange))
  }

  /// No pixel is lost along the mesh's shared edges at any scale from
  /// 1e-20 to 1e20: from inside, every pixel hits; from outside, hits and
  /// misses agree with the reference path on every pixel (measured: 0
  /// lost, 0 disagreements).
  func testIcosphere_WatertightFrom1eMinus20To1e20() throws {
    try skipUnlessLongTests()
    for precision in Precision.allCases {
      for exponent in stride(from: -20, through: 20, by: 5) {
        let s = Double("1e\(exponent)") ?? 1
        let inside = try icosphere(s, inside: true, precision)
        let depth = depthsAndNormals(inside, precision).depth
        let lost = depth.filter { !$0.isFinite }.count
        XCTAssertEqual(lost, 0, "1e\(exponent) \(precision): pixels lost")
        let outside = try icosphere(s, inside: false, precision)
        let reference = AccuracyRender.reference(
          outside, width: 48, height: 40, rays: precision)
        let (buffers, _) = AccuracyRender.render(
          outside, width: 48, height: 40, precision: precision,
          method: .stable, runs: 0)
        let m = buffers.measured(against: reference)
        XCTAssertEqual(
          m.disagreements, 0, "1e\(exponent) \(precision): disagreements")
        XCTAssertGreaterThan(m.comparedHits, 300)
      }
    }
  }

  /// The scale checks' measures taken in parts on several threads
  /// (`Extent.addInParts`, merged) are one thread's: over a group's
  /// entries, its flattened spheres and a mesh's triangles, with the
  /// smallest and largest of each measure in different parts.
  func testExtent_InPartsAsOneThread() {
    var random = SplitMix64(seed: 17)
    func next() -> Double { Double(random.next() >> 11) * 0x1p-53 }
    var objects: [SceneObject<Double>] = (0..<70_000).map { _ in
      .sphere(
        Sphere(
          center: Vector3(next(), next(), next()) * 100,
          radius: 1e-3 + next()))
    }
    var mesh = TriangleMesh<Double>()
    for _ in 0..<70_000 {
      let a = Vector3(next(), next(), next()) * 50
      mesh.append(
        Triangle(a, a + Vector3(next(), 0, 0), a + Vector3(0, next(), 1e-4)))
    }
    objects.append(.mesh(mesh))
    objects.append(.plane(Plane(normal: Vector3(0, 1, 0), offset: -3)))
    let eye = Vector3<Double>(1, 2, 300)
    func fields(_ e: LengthScale.Extent) -> [Double] {
      [
        e.largest, e.radiusSquared, e.edgeSquared, e.edgeSquaredReach,
        e.axisSquared, e.planeDistance, e.reachInAxes,
      ]
    }
    let group = Group(objects)
    var one = LengthScale.Extent(eye: eye)
    one.measure(group)
    var oneFlat = LengthScale.Extent(eye: eye)
    oneFlat.add(group.flattened())
    for threads in Self.quickCases([2, 3], half: 1) {
      var parts = LengthScale.Extent(eye: eye, threads: threads)
      parts.measure(group)
      XCTAssertEqual(fields(parts), fields(one), "group, \(threads) threads")
      var flat = LengthScale.Extent(eye: eye, threads: threads)
      flat.add(group.flattened(threads: threads))
      XCTAssertEqual(fields(flat), fields(oneFlat), "flat, \(threads) threads")
    }
  }
}
