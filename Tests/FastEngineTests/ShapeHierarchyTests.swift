import Foundation
import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Shapes of one's own (`SceneObject.shape`) in the fast engine: held in a
/// hierarchy of their boxes, as its own spheres are, not tested one by one.
final class ShapeHierarchyTests: XCTestCase {
  /// A sphere of one's own, through the hit protocol only: the course's
  /// stable quadratic (Sources/Course/Sphere.swift).
  struct Ball: Hittable {
    var center: Vector3<Double>
    var radius: Double

    func intersect(
      _ ray: Ray<Double>, after tMin: Double, before tMax: Double
    ) -> Hit<Double>? {
      let d = ray.direction
      let f = ray.origin - center
      let a = d.dot(d)
      let b = f.dot(d)
      let c = f.dot(f) - radius * radius
      let distance = (f - d * (b / a)).length
      let discriminant = a * (radius - distance) * (radius + distance)
      guard discriminant >= 0 else { return nil }
      let q = -(b + Double(signOf: b, magnitudeOf: discriminant.squareRoot()))
      let (near, far) = (min(q / a, c / q), max(q / a, c / q))
      let t = tMin < near ? near : far
      guard tMin < t && t < tMax else { return nil }
      return Hit(t: t, normal: (f + d * t).normalized(), materialIndex: 0)
    }

    var boundingBox: BoundingBox? {
      let reach = Vector3(radius, radius, radius)
      return BoundingBox(lower: center - reach, upper: center + reach)
    }
  }

  /// `count` small spheres in a slab in front of the camera, as the
  /// fast engine's spheres and as shapes of one's own.
  func scenes(count: Int) throws -> (spheres: Scene, shapes: Scene) {
    var generator = SplitMix64(seed: 0x5A_B0_11)
    var balls: [Ball] = []
    for _ in 0..<count {
      let center = Vector3(
        Double.random(in: -8...8, using: &generator),
        Double.random(in: -6...6, using: &generator),
        Double.random(in: -10...0, using: &generator))
      balls.append(
        Ball(
          center: center,
          radius: Double.random(in: 0.05...0.3, using: &generator)))
    }
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0, 0, 12), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 60))
    let spheres = Scene(
      camera: camera,
      root: Group(
        balls.map { .sphere(Sphere(center: $0.center, radius: $0.radius)) }))
    let shapes = Scene(
      camera: camera, root: Group(balls.map { .shape(Shape($0)) }))
    return (spheres, shapes)
  }

  /// 3,000 shapes draw what the same 3,000 spheres do, through a
  /// hierarchy: hit or miss alike but on a few rim pixels (where the two
  /// quadratics' roundings may decide either way; at most 0.1 %), and
  /// away from the rims (|n·d| > 0.1) depth within 10⁻⁹ relative (the
  /// Double quadratic's error, about 10³ ε here, amplified at most 10× by
  /// the grazing angle) and the same normal. The time of each render is
  /// printed beside the other's (docs/ADDING-A-SHAPE.md states it).
  func testThousandsOfShapes_InAHierarchy_AsSpheres() throws {
    let count = 3000
    let (spheres, shapes) = try scenes(count: count)
    let settings = RenderSettings(
      width: 96, height: 72, outputs: [.depth, .normals], threads: 2)
    let compiledShapes = CompiledScene<StableKernel<Double>>(shapes)
    XCTAssertNotNil(compiledShapes.shapeHierarchy)
    XCTAssertEqual(compiledShapes.boundedShapeCount, count)
    var clock = Stopwatch()
    let want = Renderer.render(
      CompiledScene<StableKernel<Double>>(spheres), settings: settings)
    let sphereSeconds = clock.lap()
    let got = Renderer.render(compiledShapes, settings: settings)
    let shapeSeconds = clock.lap()
    var (hits, disagreements) = (0, 0)
    for pixel in want.depth.indices {
      guard want.depth[pixel].isFinite == got.depth[pixel].isFinite else {
        disagreements += 1
        continue
      }
      guard want.depth[pixel].isFinite else { continue }
      hits += 1
      let column = pixel % settings.width
      let row = pixel / settings.width
      let direction = settings.camera(spheres.camera, as: Double.self)
        .rayDirection(
          x: settings.screen.x(column: column),
          y: settings.screen.y(row: row),
          aspect: Double(settings.height) / Double(settings.width))
      guard abs(want.normals[pixel].dot(direction)) > 0.1 else { continue }
      XCTAssertEqual(
        got.depth[pixel], want.depth[pixel],
        accuracy: 1e-9 * want.depth[pixel], "depth at pixel \(pixel)")
      XCTAssertGreaterThan(
        got.normals[pixel].dot(want.normals[pixel]), 1 - 1e-9,
        "normal at pixel \(pixel)")
    }
    XCTAssertLessThanOrEqual(disagreements, want.depth.count / 1000)
    XCTAssertGreaterThan(hits, want.depth.count / 4)
    print(
      "\(count) shapes of one's own: \(shapeSeconds) s; the same spheres: "
        + "\(sphereSeconds) s (×\(shapeSeconds / sphereSeconds))")
  }

  /// A shape without a bound (a plane of one's own): hit anywhere.
  struct Floor: Hittable {
    func intersect(
      _ ray: Ray<Double>, after tMin: Double, before tMax: Double
    ) -> Hit<Double>? {
      let t = (-5 - ray.origin.y) / ray.direction.y
      guard tMin < t && t < tMax else { return nil }
      return Hit(t: t, normal: Vector3(0, 1, 0), materialIndex: 0)
    }

    var boundingBox: BoundingBox? { nil }
  }

  /// A single shape, and shapes without a bound, are tested without a
  /// hierarchy; with both kinds, the bounded ones are in the hierarchy and
  /// the others after them, and a ray that misses every bounded shape
  /// still meets the unbounded one.
  func testFewOrUnboundedShapes_NoHierarchy() throws {
    let (_, one) = try scenes(count: 1)
    XCTAssertNil(CompiledScene<StableKernel<Double>>(one).shapeHierarchy)
    var floors = one
    floors.root = Group([.shape(Shape(Floor())), .shape(Shape(Floor()))])
    let unbounded = CompiledScene<StableKernel<Double>>(floors)
    XCTAssertNil(unbounded.shapeHierarchy)
    XCTAssertEqual(unbounded.boundedShapeCount, 0)

    let (_, balls) = try scenes(count: 20)
    var mixed = balls
    mixed.root = Group([.shape(Shape(Floor()))] + balls.root.objects)
    let compiled = CompiledScene<StableKernel<Double>>(mixed)
    XCTAssertNotNil(compiled.shapeHierarchy)
    XCTAssertEqual(compiled.boundedShapeCount, 20)
    XCTAssertNil(compiled.shapeBoxes.last!)
    // Straight down from (0, 100, 12), in front of every ball (they lie
    // at z ≤ 0): the ray misses the hierarchy and meets the floor at
    // y = −5, 105 below.
    // One pixel of the mit style: its ray is the view direction itself.
    let settings = RenderSettings(
      width: 1, height: 1, outputs: [.depth], style: .mit, threads: 1)
    var down = mixed
    down.camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0, 100, 12), direction: Vector3(0, -1, 0),
        up: Vector3(0, 0, -1), angle: 1))
    let depth = Renderer.render(
      CompiledScene<StableKernel<Double>>(down), settings: settings
    ).depth
    XCTAssertEqual(depth[0], 105, accuracy: 1e-9)
  }

  /// Spheres drawn by the screen tiles and shapes of one's own in one
  /// scene: the tiles' pixel loop still asks the shapes (a shortcut for
  /// scenes of spheres and planes once skipped them). The same bits as
  /// without tiles.
  func testShapesAmongProjectedSpheres_AreDrawn() throws {
    let (spheres, shapes) = try scenes(count: 40)
    var mixed = spheres
    mixed.root = Group(
      spheres.root.objects + Array(shapes.root.objects.prefix(20)) + [
        .plane(Plane(normal: Vector3(0, 1, 0), offset: -7))
      ])
    let settings = RenderSettings(
      width: 64, height: 48, outputs: [.depth, .normals], style: .course,
      threads: 1)
    let tiled = CompiledScene<StableKernel<Double>>(
      mixed, projectionThreshold: 0)
    let plain = CompiledScene<StableKernel<Double>>(mixed)
    let (got, search, _) = Renderer.renderReportingSearch(
      tiled, settings: settings)
    let (want, plainSearch, _) = Renderer.renderReportingSearch(
      plain, settings: settings)
    XCTAssertEqual(search, .screenTiles)
    XCTAssertNotEqual(plainSearch, .screenTiles)
    func differing<T: Equatable>(_ a: [T], _ b: [T]) -> Int {
      zip(a, b).count { $0 != $1 } + abs(a.count - b.count)
    }
    XCTAssertEqual(differing(got.depth, want.depth), 0, "depth pixels")
    XCTAssertEqual(differing(got.normals, want.normals), 0, "normal pixels")
    // The shapes show: without them the image differs.
    mixed.root.objects.removeAll { if case .shape = $0 { true } else { false } }
    let bare = Renderer.render(
      CompiledScene<StableKernel<Double>>(mixed), settings: settings)
    XCTAssertGreaterThan(differing(bare.depth, want.depth), 0)
  }
}
