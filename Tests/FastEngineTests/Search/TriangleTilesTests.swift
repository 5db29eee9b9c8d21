import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Triangles projected onto screen tiles (`ScreenTiles`, `triangleBox`)
/// against the triangle hierarchy, itself tested against testing every
/// triangle: every pixel's depth, normal and colour the same, bit for bit,
/// single-sample and supersampled, for meshes whose shared edges rays hit
/// exactly, coincident triangles (the first must win), triangles whose
/// planes pass near the eye (the large ones, `TrianglePlane`), triangles
/// crossing the plane of the eye, spheres and planes among them.
final class TriangleTilesTests: XCTestCase {
  /// A render whose triangles are projected or searched by their BVH.
  func render<Kernel: IntersectionKernel>(
    _: Kernel.Type, _ scene: Scene, _ settings: RenderSettings,
    projected: Bool
  ) -> (buffers: RenderBuffers<Kernel.Scalar>, search: Renderer.TriangleSearch)
  {
    let compiled = CompiledScene<Kernel>(
      scene, hierarchyThreshold: 0,
      triangleProjectionThreshold: projected ? 0 : .max)
    let rendered = Renderer.renderReportingSearch(
      compiled, settings: settings, overlapLimit: .max)
    return (rendered.buffers, rendered.triangleSearch)
  }

  /// A grid of `n`×`n` squares, each split into two triangles, of side
  /// `size` about `center` in a random orientation and jittered off its
  /// plane: every inner edge is shared, so rays through those edges test
  /// the tie rule and the watertight property.
  func grid(
    _ generator: inout SplitMix64, center: Vector3<Double>, size: Double,
    n: Int, material: Int
  ) -> [Triangle<Double>] {
    let u = generator.unitVector(Double.self)
    let v = u.cross(generator.unitVector(Double.self)).normalized()
    let w = u.cross(v)
    var points: [[Vector3<Double>]] = []
    for i in 0...n {
      var row: [Vector3<Double>] = []
      for j in 0...n {
        let bump: Double = generator.uniform(-0.2...0.2) * size / Double(n)
        row.append(
          center + u * (size * (Double(i) / Double(n) - 0.5))
            + v * (size * (Double(j) / Double(n) - 0.5)) + w * bump)
      }
      points.append(row)
    }
    var triangles: [Triangle<Double>] = []
    for i in 0..<n {
      for j in 0..<n {
        let (a, b, c, d) = (
          points[i][j], points[i + 1][j], points[i + 1][j + 1],
          points[i][j + 1]
        )
        triangles.append(Triangle(a, b, c, materialIndex: material))
        triangles.append(Triangle(a, c, d, materialIndex: material))
      }
    }
    return triangles
  }

  /// Grids and loose triangles over many binades around a random point,
  /// some repeated with another material, a few spheres and maybe a plane,
  /// the eye outside, at the edge of or inside the cluster.
  ///
  /// With `largeTriangles`, that many more triangles whose planes pass near
  /// the eye, some of them coincident twins with another material: enough
  /// for their own hierarchy (`buildLargeTriangleHierarchy`).
  func randomScene(_ generator: inout SplitMix64, largeTriangles: Int = 0)
    -> Scene?
  {
    let size: Double = generator.logUniform(1e-2, 1e4)
    let center =
      generator.unitVector(Double.self) * generator.logUniform(1, 1e6)
    var triangles: [Triangle<Double>] = []
    for _ in 0..<Int.random(in: 1...3, using: &generator) {
      let offset = generator.unitVector(Double.self) * (0.3 * size)
      triangles += grid(
        &generator, center: center + offset,
        size: size * generator.logUniform(0.05, 1),
        n: Int.random(in: 1...6, using: &generator),
        material: Int.random(in: 0..<3, using: &generator))
    }
    for _ in 0..<Int.random(in: 0...20, using: &generator) {
      let corner =
        center + generator.unitVector(Double.self)
        * (size * generator.uniform(0...0.5))
      let scale = size * generator.logUniform(1e-6, 1)
      triangles.append(
        Triangle(
          corner, corner + generator.unitVector(Double.self) * scale,
          corner + generator.unitVector(Double.self) * scale,
          materialIndex: Int.random(in: 0..<3, using: &generator)))
    }
    for _ in 0..<Int.random(in: 0...4, using: &generator) {
      var twin = triangles[Int.random(in: triangles.indices, using: &generator)]
      twin.materialIndex = Int.random(in: 0..<3, using: &generator)
      triangles.append(twin)
    }
    let away: Double =
      Bool.random(using: &generator)
      ? generator.logUniform(0.3, 1e3) : generator.uniform(0...0.3)
    let eye = center + generator.unitVector(Double.self) * (away * size)
    // A triangle whose plane passes near the eye, large beside its
    // distance (`TrianglePlane`), and one through the eye's plane.
    if Bool.random(using: &generator) {
      let normal = generator.unitVector(Double.self)
      let along = normal.cross(generator.unitVector(Double.self)).normalized()
      let across = normal.cross(along)
      let base = eye + normal * (size * 1e-5)
      // With vertex normals, so that its normal is interpolated: its hits
      // take t from its plane and come with no weights, which the normal
      // must not take from an earlier triangle's test.
      triangles.append(
        Triangle(
          base + along * (10 * size), base - along * (10 * size),
          base + across * (10 * size) + along * size,
          vertexNormals: .init(
            normal, (normal + along * 0.5).normalized(),
            (normal + across * 0.5).normalized()),
          materialIndex: 1))
    }
    for index in 0..<largeTriangles {
      if index % 5 == 4 {
        var twin = triangles[triangles.count - 1]
        twin.materialIndex = (twin.materialIndex + 1) % 3
        triangles.append(twin)
        continue
      }
      let normal = generator.unitVector(Double.self)
      let along = normal.cross(generator.unitVector(Double.self)).normalized()
      let across = normal.cross(along)
      let base =
        eye + normal * (size * generator.logUniform(1e-7, 1e-3))
        + along * (size * generator.uniform(-2...2))
      triangles.append(
        Triangle(
          base + along * (size * generator.logUniform(0.5, 20)),
          base - along * (size * generator.logUniform(0.5, 20)),
          base + across * (size * generator.uniform(-20...20)),
          materialIndex: Int.random(in: 0..<3, using: &generator)))
    }
    var objects = triangles.map { SceneObject<Double>.triangle($0) }
    for _ in 0..<Int.random(in: 0...3, using: &generator) {
      objects.insert(
        .sphere(
          Sphere(
            center: center + generator.unitVector(Double.self) * (0.4 * size),
            radius: size * generator.logUniform(1e-3, 0.2),
            materialIndex: Int.random(in: 0..<3, using: &generator))),
        at: Int.random(in: 0...objects.count, using: &generator))
    }
    if Bool.random(using: &generator) {
      objects.append(
        .plane(Plane(normal: generator.unitVector(), offset: center.y)))
    }
    let target = triangles[Int.random(in: triangles.indices, using: &generator)]
      .v0
    guard
      let camera = PerspectiveCamera<Double>(
        center: eye, direction: target - eye,
        up: generator.unitVector(Double.self),
        angle: generator.uniform(5...150))
    else { return nil }
    return Scene(
      camera: camera,
      lights: [
        .directional(direction: Vector3(-1, -2, -3), color: Vector3(1, 1, 1))
      ],
      materials: [
        Material(diffuse: Vector3(1, 0, 0)),
        Material(
          diffuse: Vector3(0, 1, 0), specular: Vector3(1, 1, 1), shininess: 8),
        Material(diffuse: Vector3(0, 0, 1)),
      ],
      root: Group(objects))
  }

  func checkRandomScenes<Kernel: IntersectionKernel>(
    _ kernel: Kernel.Type, base: UInt64, largeTriangles: Int = 0,
    seeds: Int = 12
  ) {
    forEachSeed(Self.seedCount(seeds), base: base) { generator, _ in
      guard
        let scene = randomScene(&generator, largeTriangles: largeTriangles)
      else { return }
      if largeTriangles > 0 {
        let compiled = CompiledScene<Kernel>(
          scene, hierarchyThreshold: 0, triangleProjectionThreshold: .max)
        XCTAssertGreaterThanOrEqual(
          compiled.triangles.count - compiled.ordinaryTriangleCount,
          CompiledScene<Kernel>.largeTriangleHierarchyThreshold)
        XCTAssertNotNil(compiled.largeTriangleHierarchy)
      }
      for style in ImageStyle.allCases {
        var cases: [RenderSettings] = []
        for (width, height) in [(37, 23), (1, 9), (21, 1)] {
          cases.append(
            RenderSettings(
              width: width, height: height,
              outputs: [.depth, .normals, .shaded], style: style, threads: 2))
        }
        for filter in PixelFilter.allCases {
          var settings = RenderSettings(
            width: 19, height: 11, outputs: [.depth, .shaded], style: style,
            threads: 2)
          settings.samples = 4
          settings.filter = filter
          cases.append(settings)
        }
        // Every output the mean of the samples.
        var all = RenderSettings(
          width: 19, height: 11, outputs: [.depth, .normals, .shaded],
          style: style, threads: 2)
        all.samples = 4
        all.samplesAllOutputs = true
        cases.append(all)
        for settings in cases {
          let label =
            "\(Kernel.self) \(style) \(settings.width)×\(settings.height) "
            + "\(settings.samples) samples \(settings.filter)"
          let projected = render(kernel, scene, settings, projected: true)
          XCTAssertEqual(projected.search, .screenTiles, label)
          let tree = render(kernel, scene, settings, projected: false)
          XCTAssertEqual(
            differences(projected.buffers, tree.buffers), 0, label)
        }
      }
    }
  }

  func testRandomScenes_StableDouble() {
    checkRandomScenes(StableKernel<Double>.self, base: 0x7A1)
  }
  /// Many large triangles, searched through their own hierarchy without
  /// tiles: the same images as the tiles', which test each in order.
  func testManyLargeTriangles_StableDouble() {
    checkRandomScenes(
      StableKernel<Double>.self, base: 0x7A5, largeTriangles: 40,
      seeds: 4)
  }
  /// (With RAYTRACE_LONG_TESTS: the same in Float.)
  func testManyLargeTriangles_StableFloat() throws {
    try skipUnlessLongTests()
    checkRandomScenes(
      StableKernel<Float>.self, base: 0x7A6, largeTriangles: 40,
      seeds: 4)
  }
  func testRandomScenes_StableFloat() {
    checkRandomScenes(StableKernel<Float>.self, base: 0x7A2)
  }
  /// (With RAYTRACE_LONG_TESTS: the textbook kernel in Double is also
  /// the hierarchy tests'.)
  func testRandomScenes_NaiveDouble() throws {
    try skipUnlessLongTests()
    checkRandomScenes(NaiveKernel<Double>.self, base: 0x7A3)
  }
  func testRandomScenes_NaiveFloat() {
    checkRandomScenes(NaiveKernel<Float>.self, base: 0x7A4)
  }
}
