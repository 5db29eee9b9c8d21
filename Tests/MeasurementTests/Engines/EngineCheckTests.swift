import Course
import FastEngine
import Measurement
import SceneIO
import Pipeline
import Geometry
import SceneDescription
import ExactArithmetic
import PlatformSupport
import XCTest

/// `raytrace SCENE --check` on course engines with a student's mistake: the
/// course engine's buffers changed as the mistake would change them, and
/// the probe answering as the mistaken code would.
final class EngineCheckTests: XCTestCase {
  let size = (width: 80, height: 60)

  func scene() throws -> Scene {
    try SceneReader.read(
      contentsOf: "\(projectFolder)/scenes/spheres.txt",
      options: SceneOptions(style: .course))
  }

  func settings() -> RenderSettings {
    RenderSettings(
      width: size.width, height: size.height,
      outputs: [.depth, .normals, .shaded], threads: 2)
  }

  /// The check of `course` against the fast engine, the probe changing
  /// every hit as `mistake` does.
  func check(
    _ scene: Scene, course: RenderBuffers<Double>,
    outputs: RenderOutputs = [.shaded, .normals, .depth],
    mistake: @escaping (Hit<Double>) -> Hit<Double>? = { $0 }
  ) -> EngineCheck {
    let settings = settings()
    let fast = Renderer.render(
      CompiledScene<StableKernel<Double>>(scene), settings: settings)
    return EngineCheck(
      scene: scene, course: course, fast: fast, style: .course,
      outputs: outputs, depthRange: nil, tolerance: 2
    ) { column, row in
      let (ray, hits) = CourseEngine.probe(
        scene, settings: settings, column: column, row: row)
      return (
        ray,
        hits.compactMap { found in mistake(found.hit).map { (found.index, $0) }
        }
      )
    }
  }

  func testTheCourseEngine_PassesItsOwnCheck() throws {
    let scene = try scene()
    let course = CourseEngine.render(scene, settings: settings())
    for output in check(scene, course: course).outputs {
      XCTAssertEqual(output.comparison.pattern, .identical, output.name)
      XCTAssertTrue(output.pixel.isEmpty)
    }
  }

  /// A normal not normalised (twice as long): the normals image differs,
  /// and the first differing pixel names the same object and t and the
  /// normal's length; a normal of the right direction is no "turned"
  /// normal, too long or too short.
  func testNormalNotNormalised_Named() throws {
    let scene = try scene()
    for scale in [2.0, 0.5] {
      var course = CourseEngine.render(scene, settings: settings())
      course.normals = course.normals.map { $0 * scale }
      let check = check(scene, course: course, outputs: [.normals]) { hit in
        var long = hit
        long.normal = hit.normal * scale
        return long
      }
      let normals = try XCTUnwrap(check.outputs.first)
      XCTAssertLessThan(normals.comparison.share, 0.999)
      XCTAssertEqual(normals.turnedNormals, 0, "\(scale): the same directions")
      let verdict = try XCTUnwrap(normals.pixel.last)
      XCTAssertTrue(
        verdict.contains("has length \(Float(scale)), not 1"), verdict)
      XCTAssertTrue(normals.pixel[1].contains("object"), normals.pixel[1])
    }
  }

  /// A sign error that loses the spheres: the course engine misses what
  /// the fast engine hits, named by object and kind.
  func testSphereLost_Named() throws {
    let scene = try scene()
    var settings = settings()
    settings.outputs = [.depth]
    var course = CourseEngine.render(scene, settings: settings)
    let fast = Renderer.render(
      CompiledScene<StableKernel<Double>>(scene), settings: settings)
    // Where the fast engine's nearest is a sphere, the mistaken course
    // engine sees only what lies behind: here, nothing.
    let lost = { (hit: Hit<Double>) -> Hit<Double>? in nil }
    course.depth = course.depth.map { _ in .infinity }
    course.normals = Array(repeating: .zero, count: fast.depth.count)
    course.color = Array(repeating: scene.background, count: fast.depth.count)
    let check = check(scene, course: course, mistake: lost)
    let depth = try XCTUnwrap(check.outputs.last)
    XCTAssertEqual(depth.name, "depth")
    let verdict = try XCTUnwrap(depth.pixel.last)
    XCTAssertTrue(verdict.contains("the course engine misses object"), verdict)
    XCTAssertTrue(depth.pixel[2].contains("Sphere"), depth.pixel[2])
  }

  /// Rows in the opposite order: the pattern says so.
  func testRowsFlipped_Named() throws {
    let scene = try scene()
    var course = CourseEngine.render(scene, settings: settings())
    var flipped = course.color
    for row in 0..<size.height {
      for column in 0..<size.width {
        flipped[row * size.width + column] =
          course.color[(size.height - 1 - row) * size.width + column]
      }
    }
    course.color = flipped
    let shaded = try XCTUnwrap(
      check(scene, course: course, outputs: [.shaded]).outputs.first)
    XCTAssertEqual(shaded.comparison.pattern, .flippedRows)
  }

  /// A normal turned inside out: the course style's normals image (|n|)
  /// is the same, yet the check finds the turned normals and says what.
  func testNormalTurnedInsideOut_Named() throws {
    let scene = try scene()
    var course = CourseEngine.render(scene, settings: settings())
    course.normals = course.normals.map { -$0 }
    let check = check(scene, course: course, outputs: [.normals]) { hit in
      var turned = hit
      turned.normal = -hit.normal
      return turned
    }
    let normals = try XCTUnwrap(check.outputs.first)
    XCTAssertEqual(normals.comparison.pattern, .identical, "|n| hides it")
    XCTAssertGreaterThan(normals.turnedNormals, 100)
    XCTAssertFalse(normals.passes(need: 0.999))
    let verdict = try XCTUnwrap(normals.pixel.last)
    XCTAssertTrue(verdict.contains("the normals differ"), verdict)
  }

  /// Pixels one engine hits and the other misses are found whatever the
  /// images' 8-bit levels say (a depth beyond the course's 40-unit cutoff
  /// is black either way): here the course engine misses two pixels of the
  /// scene and hits one the fast engine misses.
  func testHitOrMissPixels_AreCountedWhereverTheyAre() throws {
    let scene = try scene()
    let fast = Renderer.render(
      CompiledScene<StableKernel<Double>>(scene), settings: settings())
    var course = CourseEngine.render(scene, settings: settings())
    XCTAssertEqual(
      EngineCheck.hitOrMissPixels(course: course, fast: fast), [],
      "the course's own code agrees")
    let hits = course.depth.indices.filter { course.depth[$0].isFinite }
    let misses = course.depth.indices.filter { !course.depth[$0].isFinite }
    let changed = [hits[10], hits[200], misses[5]].sorted()
    course.depth[hits[10]] = .infinity
    course.depth[hits[200]] = .infinity
    course.depth[misses[5]] = 100
    XCTAssertEqual(
      EngineCheck.hitOrMissPixels(course: course, fast: fast), changed)
  }
}
