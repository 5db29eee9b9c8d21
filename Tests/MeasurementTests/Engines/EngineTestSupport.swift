import Course
import FastEngine
import SceneIO
import Pipeline
import Geometry
import SceneDescription
import Foundation
import TestSupport
import XCTest

// The course's shapes, by the names the course gives them: RayTracer's
// scene description has generic types of the same names, which these
// declarations of the test module's own shadow.
typealias Sphere = Course.Sphere
typealias Plane = Course.Plane
typealias Triangle = Course.Triangle
typealias TriangleMesh = Course.TriangleMesh
typealias Group = Course.Group
typealias Transform = Course.Transform

/// The package's folder.
let projectFolder = ProjectFiles.projectFolder

/// The course's reference material beside the package, when it is there
/// (CI has it; a fresh clone does not).
let sharedReference = "\(projectFolder)/../shared/reference"

/// The files of `folder` whose names end in one of `suffixes`, sorted.
func files(in folder: String, endingIn suffixes: [String]) -> [String] {
  let names =
    (try? FileManager.default.contentsOfDirectory(atPath: folder))
    ?? []
  return names.filter { name in suffixes.contains { name.hasSuffix($0) } }
    .sorted().map { "\(folder)/\($0)" }
}

/// The same scene drawn by both engines, in Double.
struct BothEngines {
  var course: RenderBuffers<Double>
  var fast: RenderBuffers<Double>
  var style: ImageStyle

  /// With `samples` > 1, every output is the mean of each pixel's samples
  /// (`RenderSettings.samplesAllOutputs`).
  init(
    _ scene: Scene, width: Int, height: Int, style: ImageStyle,
    samples: Int = 1
  ) {
    var settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals, .shaded],
      style: style, threads: 2)
    settings.samples = samples
    settings.samplesAllOutputs = true
    course = CourseEngine.render(scene, settings: settings)
    fast = Renderer.render(
      CompiledScene<StableKernel<Double>>(scene), settings: settings)
    self.style = style
  }

  init(
    contentsOf path: String, width: Int, height: Int, style: ImageStyle,
    samples: Int = 1
  ) throws {
    let scene = try SceneReader.read(
      contentsOf: path, options: SceneOptions(style: style))
    self.init(
      scene, width: width, height: height, style: style, samples: samples)
  }

  /// The 8-bit images (shaded, normals, depth) of each engine, the depth
  /// image over the course engine's range.
  var images: [(name: String, course: Image8, fast: Image8)] {
    let range = style.depthRange(course.depth, given: nil)
    return [
      ("shaded", style.colorImage(course), style.colorImage(fast)),
      ("normals", style.normalImage(course), style.normalImage(fast)),
      (
        "depth", style.depthImage(course, range: range),
        style.depthImage(fast, range: range)
      ),
    ]
  }
}

/// The share of pixels whose every channel differs by at most `levels`.
func shareWithin(_ levels: Int, _ a: Image8, _ b: Image8) -> Double {
  precondition(a.width == b.width && a.height == b.height)
  var within = 0
  for row in 0..<a.height {
    for column in 0..<a.width {
      let (p, q) = (a[column, row], b[column, row])
      if abs(Int(p.0) - Int(q.0)) <= levels
        && abs(Int(p.1) - Int(q.1)) <= levels
        && abs(Int(p.2) - Int(q.2)) <= levels
      {
        within += 1
      }
    }
  }
  return Double(within) / Double(a.width * a.height)
}
