import XCTest

@testable import RayTracer

/// The course engine (the model's hit protocol for every object of every
/// pixel) against the fast engine, as `raytrace` runs them: the same
/// bytes on every project scene and every scene of the stiff suite, in
/// both methods, single-sample and supersampled, with every output raw
/// (NPY keeps every bit of t, the normal and the colour).
final class CourseEngineTests: XCTestCase {
  static var projectFolder: String {
    // Tests/RayTracerTests/Render/CourseEngineTests.swift → the package.
    var parts = "\(#filePath)".split(
      separator: "/", omittingEmptySubsequences: false)
    parts.removeLast(4)
    return parts.joined(separator: "/")
  }

  /// Every scene of `scenes/` (both formats) and `scenes/stiff/`.
  static func projectScenes() throws -> [String] {
    var paths: [String] = []
    for folder in ["scenes", "scenes/stiff"] {
      let path = "\(projectFolder)/\(folder)"
      for name in try listFolder(path).sorted()
      where name.hasSuffix(".txt") || name.hasSuffix(".plist") {
        paths.append("\(path)/\(name)")
      }
    }
    return paths
  }

  /// The three raw outputs of `engine` rendering `path`.
  func render(
    _ path: String, engine: Engine, method: IntersectionMethod,
    samples: Int, style: ImageStyle = .course
  ) throws -> [[UInt8]] {
    let scene = try SceneReader.read(
      contentsOf: path, options: SceneOptions(style: style))
    var settings = RenderSettings(
      width: 40, height: 30, outputs: [], style: style, method: method,
      threads: 2)
    settings.samples = samples
    settings.engine = engine
    let folder =
      FileManager.default.temporaryDirectory.path
      + "/course-engine-\(getpid())-\(engine)"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
    defer { try? FileManager.default.removeItem(atPath: folder) }
    let kinds: [RenderOutputs] = [.depth, .normals, .shaded]
    let files = kinds.enumerated().compactMap { index, kind in
      OutputFile(kind: kind, path: "\(folder)/\(index).npy")
    }
    _ = try RenderJob.run(scene: scene, settings: settings, files: files)
    return try files.map {
      Array(try Data(contentsOf: URL(fileURLWithPath: $0.path)))
    }
  }

  func assertSameImages(
    method: IntersectionMethod, samples: Int, style: ImageStyle = .course
  ) throws {
    let scenes = try Self.projectScenes()
    XCTAssertGreaterThanOrEqual(scenes.count, 25, "the project's scenes")
    for path in scenes {
      let name = (path as NSString).lastPathComponent
      let course = try render(
        path, engine: .course, method: method, samples: samples, style: style)
      let fast = try render(
        path, engine: .fast, method: method, samples: samples, style: style)
      for (output, kind) in zip(course.indices, ["depth", "normals", "color"]) {
        XCTAssertEqual(
          course[output], fast[output],
          "\(name) \(method) \(samples) sample(s) \(style): \(kind) differs")
      }
    }
  }

  func testSameImages_Stable() throws {
    try assertSameImages(method: .stable, samples: 1)
  }

  func testSameImages_Naive() throws {
    try assertSameImages(method: .naive, samples: 1)
  }

  func testSameImages_Supersampled() throws {
    try assertSameImages(method: .stable, samples: 4)
  }

  func testSameImages_MitStyle() throws {
    try assertSameImages(method: .stable, samples: 1, style: .mit)
  }

  /// What the course engine draws is what `Sphere.intersect` returns: its
  /// depth at each pixel is the t of the pixel's ray against the scene's
  /// one sphere, computed here by the model directly.
  func testDraws_WhatSphereIntersectReturns() throws {
    let scene = try SceneParser.parse(
      contentsOf: "\(Self.projectFolder)/scenes/single-sphere.txt")
    guard let sphere = scene.root.flattened().spheres.first else {
      return XCTFail("the scene has a sphere")
    }
    var settings = RenderSettings(width: 32, height: 24, outputs: [.depth])
    settings.engine = .course
    let buffers = CourseEngine.render(scene, settings: settings)
    var hits = 0
    for row in 0..<24 {
      for column in 0..<32 {
        let x: Double = ImageStyle.course.screenX(column: column, width: 32)
        let y: Double = ImageStyle.course.screenY(row: row, height: 24)
        let ray = Ray(
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
