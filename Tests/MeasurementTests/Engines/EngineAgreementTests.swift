import Course
import Foundation
import FastEngine
import SceneIO
import Pipeline
import Geometry
import SceneDescription
import ExactArithmetic
import PlatformSupport
import TestSupport
import XCTest

/// The course engine against the fast engine, measured rather than forced:
/// their numerics differ (Cramer's rule against the watertight triangle
/// test, the course's quadratic against the fast engine's camera-relative
/// one, M⁻¹ against transforms baked into the world), so their images are
/// held to a bound, stated here and in docs/ENGINES.md:
/// - every 8-bit image (shaded, normals, depth) within 1 level on at least
///   99.9 % of pixels: only pixels on a silhouette, where the two tests of
///   a grazing ray may disagree, can differ more;
/// - depth within `depthBound` relative where both hit away from
///   silhouettes (the pixel and its four neighbours hit in both engines,
///   with the same normal to within 10⁻⁶).
final class EngineAgreementTests: XCTestCase {
  static let levels = 1
  static let share = 0.999
  /// 2⁻³⁰ ≈ 9.3·10⁻¹⁰ relative, about 4·10⁶ ε: the two triangle tests each
  /// lose digits as a triangle grows beside its distance (ACCURACY.md), and
  /// the course's sphere keeps the cancelling c = |f|² − r² that the fast
  /// engine computes in twice the precision. Measured at 160×160: at most
  /// 3.7·10⁻¹³ (planet-1e4, where c cancels), 3·10⁻¹⁵ on every other
  /// project, stiff and reference scene.
  static let depthBound = 0x1p-30

  /// The stiff suite's scenes that the course engine is meant for: no
  /// lengths beyond 10¹⁰ or below 10⁻¹⁰ of each other, where its Double
  /// arithmetic without scaling keeps its digits (ENGINES.md).
  static let moderateStiffScenes = [
    "camera-inside-sphere", "camera-on-plane", "far-sphere-1e2",
    "far-sphere-1e4", "far-triangle-1e4", "grazing-plane", "grazing-sphere",
    "grazing-triangle", "ground-triangle", "parallel-plane", "planet-1e4",
    "scaled-small", "sphere-behind-camera", "translated-far",
    "unit-sphere-1e-10", "unit-sphere-1e10",
  ]

  /// The images' size: 160 pixels square in CI (RAYTRACE_LONG_TESTS),
  /// 96 in a student's `swift test`, where the fast engine runs
  /// unoptimised (a third of the time; the share within a level is a fraction
  /// of the pixels either way).
  static let size = runsLongTests ? 160 : 96

  /// Compares both engines on `path`; returns a line of what was measured.
  @discardableResult
  func assertAgree(
    _ path: String, style: ImageStyle, size: Int = EngineAgreementTests.size,
    samples: Int = 1, file: StaticString = #filePath, line: UInt = #line
  ) throws -> String {
    let both = try BothEngines(
      contentsOf: path, width: size, height: size, style: style,
      samples: samples)
    let name = (path as NSString).lastPathComponent
    var measured = name
    for (output, course, fast) in both.images {
      let share = shareWithin(Self.levels, course, fast)
      measured += String(format: " %@ %.5f", output, share)
      XCTAssertGreaterThanOrEqual(
        share, Self.share, "\(name): \(output) within \(Self.levels) level",
        file: file, line: line)
    }
    let worst = worstDepthDifference(both, size: size)
    measured += String(format: " depth %.2e", worst)
    XCTAssertLessThanOrEqual(
      worst, Self.depthBound, "\(name): relative depth difference",
      file: file, line: line)
    return measured
  }

  /// The largest |t_course − t_fast| / t_fast away from silhouettes.
  func worstDepthDifference(_ both: BothEngines, size: Int) -> Double {
    var worst = 0.0
    func interior(_ pixel: Int) -> Bool {
      let (row, column) = pixel.quotientAndRemainder(dividingBy: size)
      guard row > 0, column > 0, row < size - 1, column < size - 1 else {
        return false
      }
      for other in [pixel, pixel - 1, pixel + 1, pixel - size, pixel + size] {
        guard both.course.depth[other].isFinite,
          both.fast.depth[other].isFinite,
          (both.course.normals[other] - both.fast.normals[other]).length < 1e-6
        else { return false }
      }
      return true
    }
    for pixel in both.course.depth.indices where interior(pixel) {
      let (a, b) = (both.course.depth[pixel], both.fast.depth[pixel])
      worst = max(worst, abs(a - b) / b)
    }
    return worst
  }

  func testProjectScenes() throws {
    let scenes = files(
      in: "\(projectFolder)/scenes", endingIn: [".txt", ".plist"])
    XCTAssertGreaterThanOrEqual(scenes.count, 10)
    for path in scenes {
      print(try assertAgree(path, style: .course))
    }
  }

  func testProjectScenes_MitStyle() throws {
    for path in files(in: "\(projectFolder)/scenes", endingIn: [".txt"]) {
      print(try assertAgree(path, style: .mit))
    }
  }

  /// Every output the mean of 4 samples a pixel (`--sample-all-outputs`):
  /// the same bound, at a smaller size (four times the rays). Averaged,
  /// depth and normals stay within it away from silhouettes, where every
  /// sample hits the same surface in both engines.
  func testProjectScenes_EveryOutputSupersampled() throws {
    let scenes = files(
      in: "\(projectFolder)/scenes", endingIn: [".txt", ".plist"])
    XCTAssertGreaterThanOrEqual(scenes.count, 10)
    for path in scenes {
      print(
        try assertAgree(
          path, style: .course, size: runsLongTests ? 64 : 48, samples: 4))
    }
  }

  func testStiffSuite_ModerateCases() throws {
    for name in Self.quickCases(Self.moderateStiffScenes) {
      print(
        try assertAgree(
          "\(projectFolder)/scenes/stiff/\(name).txt", style: .course))
    }
  }

  /// The course's own scenes, where they are beside the package (CI), with
  /// RAYTRACE_LONG_TESTS.
  func testReferenceScenes() throws {
    try XCTSkipUnless(
      runsLongTests, "a long case: RAYTRACE_LONG_TESTS=1 swift test runs it")
    let mit = files(in: "\(sharedReference)/mit", endingIn: [".txt"])
    let course = files(in: "\(sharedReference)/course", endingIn: [".txt"])
    let swift = files(
      in: "\(sharedReference)/swift-course/Scenes", endingIn: [".plist"])
    try XCTSkipIf(
      mit.isEmpty && swift.isEmpty, "no ../shared/reference beside the package")
    for path in mit { print(try assertAgree(path, style: .mit)) }
    for path in course + swift { print(try assertAgree(path, style: .course)) }
  }

  /// What the course engine draws is what `Sphere.intersect` returns: its
  /// depth at each pixel is the t of the pixel's ray against the scene's
  /// one sphere, asked here directly.
  func testDraws_WhatSphereIntersectReturns() throws {
    let scene = try SceneReader.read(
      contentsOf: "\(projectFolder)/scenes/single-sphere.txt",
      options: SceneOptions(style: .course))
    guard case .sphere(let described) = scene.root.objects.first else {
      return XCTFail("the scene's one object is a sphere")
    }
    let sphere = Sphere(center: described.center, radius: described.radius)
    let settings = RenderSettings(width: 32, height: 24, outputs: [.depth])
    let buffers = CourseEngine.render(scene, settings: settings)
    var hits = 0
    for row in 0..<24 {
      for column in 0..<32 {
        let x: Double = settings.screen.x(column: column)
        let y: Double = settings.screen.y(row: row)
        let ray = Ray<Double>(
          origin: scene.camera.center,
          direction: scene.camera.rayDirection(x: x, y: y, aspect: 0.75))
        let t = sphere.intersect(ray, after: 0, before: .infinity)?.t
        XCTAssertEqual(buffers.depth[row * 32 + column], t ?? .infinity)
        if t != nil { hits += 1 }
      }
    }
    XCTAssertGreaterThan(hits, 32 * 24 / 10, "the sphere fills the view")
  }
}
