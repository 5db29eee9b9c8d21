import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Spheres projected onto screen tiles (`ScreenTiles`) against the searches
/// already shown equal to testing every sphere (the BVH, and culling per
/// tile): every pixel's depth, normal and colour the same, bit for bit,
/// ties between coincident spheres included, supersampled renders too; and,
/// sphere by sphere, every pixel whose ray the kernel reports hitting lies
/// in the sphere's box.
final class ScreenTilesTests: XCTestCase {
  /// A render of `scene` with the spheres searched as `search` asks:
  /// projected (threshold 0), by BVH (threshold 0), or culled per tile.
  /// Projection is never declined here unless `overlapLimit` is given:
  /// the small images of these tests are covered many times over.
  func render<Kernel: IntersectionKernel>(
    _: Kernel.Type, _ scene: Scene, _ settings: RenderSettings,
    _ search: Renderer.SphereSearch, overlapLimit: Int = .max
  ) -> (buffers: RenderBuffers<Kernel.Scalar>, search: Renderer.SphereSearch) {
    let compiled = CompiledScene<Kernel>(
      scene, hierarchyThreshold: search == .hierarchy ? 0 : .max,
      projectionThreshold: search == .screenTiles ? 0 : .max)
    let rendered = Renderer.renderReportingSearch(
      compiled, settings: settings, overlapLimit: overlapLimit)
    return (rendered.buffers, rendered.search)
  }

  /// Projection and the BVH (and, for few spheres, culling) agree on every
  /// pixel of `scene`.
  func assertSameImages<Kernel: IntersectionKernel>(
    _ kernel: Kernel.Type, _ scene: Scene, _ settings: RenderSettings,
    _ label: String, file: StaticString = #filePath, line: UInt = #line
  ) {
    let projected = render(kernel, scene, settings, .screenTiles)
    XCTAssertEqual(
      projected.search, .screenTiles, label, file: file, line: line)
    let tree = render(kernel, scene, settings, .hierarchy)
    XCTAssertEqual(
      differences(projected.buffers, tree.buffers), 0,
      "\(label) against the BVH",
      file: file, line: line)
    if scene.root.flattened().spheres.count < 400 {
      let culled = render(kernel, scene, settings, .culledPerTile)
      XCTAssertEqual(
        differences(projected.buffers, culled.buffers), 0,
        "\(label) against culling",
        file: file, line: line)
    }
  }

  /// Spheres of sizes over many binades around a random point, some
  /// repeated exactly with another material (ties the first must win), a
  /// plane through the cluster, and an eye outside, at the edge of or
  /// inside the cluster looking at one sphere with a tilted `up` (so the
  /// mit style's vertical axis is not perpendicular to the view).
  func randomScene(_ generator: inout SplitMix64, count: Int) -> Scene? {
    let size: Double = generator.logUniform(1e-2, 1e4)
    let center =
      generator.unitVector(Double.self) * generator.logUniform(1, 1e6)
    var spheres: [Sphere<Double>] = []
    for index in 0..<count {
      if index > 0 && Int.random(in: 0..<8, using: &generator) == 0 {
        var twin = spheres[Int.random(in: spheres.indices, using: &generator)]
        twin.materialIndex = Int.random(in: 0..<3, using: &generator)
        spheres.append(twin)
        continue
      }
      let offset = Vector3<Double>(
        generator.uniform(-0.5...0.5), generator.uniform(-0.5...0.5),
        generator.uniform(-0.5...0.5))
      spheres.append(
        Sphere(
          center: center + offset * size,
          radius: generator.logUniform(1e-7 * size, 0.4 * size),
          materialIndex: Int.random(in: 0..<3, using: &generator)))
    }
    let away: Double =
      Bool.random(using: &generator)
      ? generator.logUniform(0.3, 1e3) : generator.uniform(0...0.3)
    let eye = center + generator.unitVector(Double.self) * (away * size)
    let target = spheres[Int.random(in: spheres.indices, using: &generator)]
      .center
    let up = generator.unitVector(Double.self)
    guard
      let camera = PerspectiveCamera<Double>(
        center: eye, direction: target - eye, up: up,
        angle: generator.uniform(5...150))
    else { return nil }
    var objects = spheres.map { SceneObject<Double>.sphere($0) }
    if Bool.random(using: &generator) {
      objects.append(
        .plane(Plane(normal: generator.unitVector(), offset: center.y)))
    }
    return Scene(
      camera: camera,
      lights: [
        .directional(direction: Vector3(-1, -2, -3), color: Vector3(1, 1, 1))
      ],
      materials: [
        Material(diffuse: Vector3(1, 0, 0)),
        Material(diffuse: Vector3(0, 1, 0)),
        Material(diffuse: Vector3(0, 0, 1)),
      ],
      root: Group(objects))
  }

  func checkRandomScenes<Kernel: IntersectionKernel>(
    _ kernel: Kernel.Type, base: UInt64
  ) {
    forEachSeed(Self.seedCount(12), base: base) { generator, _ in
      guard
        let scene = randomScene(
          &generator, count: Int.random(in: 1...120, using: &generator))
      else { return }
      for style in ImageStyle.allCases {
        // Sizes that are not multiples of a tile, and single rows and columns.
        for (width, height) in [(37, 23), (16, 4), (1, 9), (21, 1)] {
          let settings = RenderSettings(
            width: width, height: height, outputs: [.depth, .normals, .shaded],
            style: style, threads: 2)
          assertSameImages(
            kernel, scene, settings,
            "\(Kernel.self) \(style) \(width)×\(height)")
        }
        // Supersampled: boxes and culled pyramids widened by the filter's
        // reach must hold every sample of every pixel.
        for filter in PixelFilter.allCases {
          var settings = RenderSettings(
            width: 19, height: 11, outputs: [.depth, .shaded], style: style,
            threads: 2)
          settings.samples = 4
          settings.filter = filter
          assertSameImages(
            kernel, scene, settings,
            "\(Kernel.self) \(style) 4 samples, \(filter)")
        }
        // Depth and normals the means of the samples, nothing shaded.
        var all = RenderSettings(
          width: 19, height: 11, outputs: [.depth, .normals], style: style,
          threads: 2)
        all.samples = 4
        all.samplesAllOutputs = true
        assertSameImages(
          kernel, scene, all, "\(Kernel.self) \(style) every output sampled")
      }
    }
  }

  func testRandomScenes_StableDouble() {
    checkRandomScenes(StableKernel<Double>.self, base: 0x5C1)
  }
  func testRandomScenes_StableFloat() {
    checkRandomScenes(StableKernel<Float>.self, base: 0x5C2)
  }
  /// (With RAYTRACE_LONG_TESTS: the textbook kernel in Double is also
  /// the hierarchy tests'.)
  func testRandomScenes_NaiveDouble() throws {
    try skipUnlessLongTests()
    checkRandomScenes(NaiveKernel<Double>.self, base: 0x5C3)
  }
  func testRandomScenes_NaiveFloat() {
    checkRandomScenes(NaiveKernel<Float>.self, base: 0x5C4)
  }

  /// The stiff suite's tiny far spheres, planets, grazing and inside views.
  func testStiffScenes_SameImages() throws {
    try skipUnlessLongTests()
    for name in ProjectFiles.stiffScenes {
      let scene = try SceneParser.parse(
        contentsOf: "\(ProjectFiles.stiffFolder)/\(name).txt")
      for style in ImageStyle.allCases {
        let settings = RenderSettings(
          width: 48, height: 36, outputs: [.depth, .normals, .shaded],
          style: style, threads: 2)
        assertSameImages(
          StableKernel<Double>.self, scene, settings, "\(name) \(style) double")
        assertSameImages(
          StableKernel<Float>.self, scene, settings, "\(name) \(style) float")
        assertSameImages(
          NaiveKernel<Float>.self, scene, settings,
          "\(name) \(style) naive float")
      }
    }
  }

  /// `count` spheres one behind the other on the view's axis, each at
  /// least `radius` and filling a 30° view, seen from the origin.
  func sphereStack(_ count: Int, radius: Double) -> Scene? {
    let spheres = (0..<count).map { index in
      SceneObject<Double>.sphere(
        Sphere(
          center: Vector3(0, 0, -10 - 3 * Double(index)),
          radius: radius + Double(index)))
    }
    guard
      let camera = PerspectiveCamera<Double>(
        center: .zero, direction: Vector3(0, 0, -1), up: Vector3(0, 1, 0),
        angle: 30)
    else { return nil }
    return Scene(camera: camera, root: Group(spheres))
  }

  /// The tiles decline `scene` (their coverage then, for the message),
  /// the render builds the hierarchy instead, and the images are the
  /// hierarchy's.
  func assertDeclinesToTheHierarchy(
    _ scene: Scene, _ settings: RenderSettings,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    let compiled = CompiledScene<StableKernel<Double>>(
      scene, projectionThreshold: 0)
    let camera = PerspectiveCamera<Double>(compiled.camera)
    XCTAssertNil(
      ScreenTiles(compiled, camera: camera, settings: settings)?.coveredPixels,
      "covered pixels of tiles that should have declined", file: file,
      line: line)
    let fallback = render(
      StableKernel<Double>.self, scene, settings, .screenTiles,
      overlapLimit: ScreenTiles<StableKernel<Double>>.overlapLimit)
    XCTAssertEqual(fallback.search, .hierarchy, file: file, line: line)
    let tree = render(StableKernel<Double>.self, scene, settings, .hierarchy)
    XCTAssertEqual(
      differences(fallback.buffers, tree.buffers), 0, file: file, line: line)
  }

  /// 64 spheres, each filling the view, cover a 40×30 image 64 times:
  /// over the overlap limit. Without the limit the tiles count it exactly.
  func testHeavyOverlap_DeclinesToTheHierarchy() throws {
    let scene = try XCTUnwrap(sphereStack(64, radius: 5))
    let settings = RenderSettings(
      width: 40, height: 30, outputs: [.depth, .normals], threads: 2)
    assertDeclinesToTheHierarchy(scene, settings)
    let compiled = CompiledScene<StableKernel<Double>>(
      scene, projectionThreshold: 0)
    let accepted = ScreenTiles(
      compiled, camera: PerspectiveCamera<Double>(compiled.camera),
      settings: settings,
      overlapLimit: 1000)
    XCTAssertEqual(accepted?.coveredPixels, 64 * 40 * 30)
  }

  /// A column one pixel wide and 4,096 high: 16 spheres filling it cover
  /// it 16 times (under the overlap limit) but list each sphere in all
  /// 1,024 of its tiles, more entries than twice the pixels and spheres:
  /// declined for memory.
  func testManyTilesPerSphere_DeclinesToTheHierarchy() throws {
    let scene = try XCTUnwrap(sphereStack(16, radius: 100))
    assertDeclinesToTheHierarchy(
      scene,
      RenderSettings(
        width: 1, height: 4096, outputs: [.depth, .normals], threads: 2))
  }

  /// From 2¹⁴ spheres two threads sort them into tiles, each half of the
  /// scene on its own: each tile must still list its spheres in scene
  /// order, or coincident spheres on both sides of the split would swap
  /// which one is seen.
  func testTwoThreadBinning_KeepsSceneOrder() {
    var generator = SplitMix64(seed: 0x71E5)
    let half = 1 << 13
    var spheres: [Sphere<Double>] = (0..<half).map { _ in
      Sphere(
        center: Vector3(
          generator.uniform(-1...1), generator.uniform(-1...1),
          generator.uniform(-3 ... -1)),
        radius: generator.uniform(0.005...0.02), materialIndex: 0)
    }
    // The second half repeats the first with the other material.
    spheres += spheres.map {
      Sphere(center: $0.center, radius: $0.radius, materialIndex: 1)
    }
    guard
      let camera = PerspectiveCamera<Double>(
        center: Vector3(0, 0, 1), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 60)
    else { return XCTFail("camera") }
    let scene = Scene(
      camera: camera,
      materials: [
        Material(diffuse: Vector3(1, 0, 0)),
        Material(diffuse: Vector3(0, 1, 0)),
      ],
      root: Group(spheres.map { .sphere($0) }))
    let settings = RenderSettings(
      width: 64, height: 48, outputs: [.shaded], threads: 2)
    let projected = render(
      StableKernel<Double>.self, scene, settings, .screenTiles)
    XCTAssertEqual(projected.search, .screenTiles)
    let green = projected.buffers.color.filter { $0.y > 0 }.count
    XCTAssertEqual(
      green, 0, "pixels showing the later of two coincident spheres")
    XCTAssertGreaterThan(projected.buffers.color.filter { $0.x > 0 }.count, 100)
    let tree = render(StableKernel<Double>.self, scene, settings, .hierarchy)
    XCTAssertEqual(differences(projected.buffers, tree.buffers), 0)
    var oneThread = settings
    oneThread.threads = 1
    let single = render(
      StableKernel<Double>.self, scene, oneThread, .screenTiles)
    XCTAssertEqual(
      differences(projected.buffers, single.buffers), 0,
      "one thread against two")
  }
}
