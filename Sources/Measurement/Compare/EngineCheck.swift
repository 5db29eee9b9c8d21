import FastEngine
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// The course engine's images against the fast engine's, output by output,
/// and what each engine hit at the first pixel where they differ
/// (`raytrace SCENE --check`).
package struct EngineCheck {
  /// What one engine hit along a pixel's ray: the object's index in the
  /// scene's group and its kind, t and the normal; nil for a miss.
  package struct Found {
    package var index: Int
    package var kind: String
    package var materialIndex: Int
    package var t: Double
    package var normal: Vector3<Double>
  }

  /// One output's comparison, and its first differing pixel's report.
  package struct Output {
    package var name: String
    package var comparison: ImageComparison
    package var pixel: [String]
    /// For normals: pixels where both engines hit and the normals point
    /// more than 2.6° apart, which an image of |n| can hide (a normal
    /// turned inside out draws the same |n|). Directions only: a normal of
    /// the right direction and the wrong length is the first pixel's
    /// report ("normalise it"), not a turn.
    package var turnedNormals = 0
    /// Whether the output matches: its image within the tolerance on
    /// `need` of the pixels, and no normal turned.
    package func passes(need: Double) -> Bool {
      comparison.share >= need && turnedNormals == 0
    }
  }

  package var outputs: [Output] = []

  /// Compares the `outputs` (8-bit, as the style draws them; depth over
  /// `depthRange`, or the course engine's own range) of the two renders,
  /// whose buffers hold depth, normals and colour.
  ///
  /// - Parameter probe: the ray of a pixel and the course engine's hit
  ///   there, object by object (`CourseEngine.probe`).
  package init(
    scene: Scene, course: RenderBuffers<Double>, fast: RenderBuffers<Double>,
    style: ImageStyle, outputs requested: RenderOutputs,
    depthRange: ClosedRange<Double>?, tolerance: Double,
    probe: (Int, Int) -> (
      ray: Ray<Double>, hits: [(index: Int, hit: Hit<Double>)]
    )
  ) {
    let range = style.depthRange(course.depth, given: depthRange)
    var images: [(String, Image8, Image8)] = []
    if requested.contains(.shaded) {
      images.append(
        ("shaded", style.colorImage(course), style.colorImage(fast)))
    }
    if requested.contains(.normals) {
      images.append(
        ("normals", style.normalImage(course), style.normalImage(fast)))
    }
    if requested.contains(.depth) {
      images.append(
        (
          "depth", style.depthImage(course, range: range),
          style.depthImage(fast, range: range)
        ))
    }
    for (name, a, b) in images {
      let comparison = ImageComparison(
        ReadImage(a), ReadImage(b), tolerance: tolerance)
      var lines: [String] = []
      var turned = 0
      var firstTurned: (column: Int, row: Int)?
      if name == "normals" {
        for index in course.normals.indices
        where course.depth.indices.contains(index)
          && course.depth[index].isFinite && fast.depth[index].isFinite
          && Self.cosine(course.normals[index], fast.normals[index]) < 0.999
        {
          turned += 1
          if firstTurned == nil {
            firstTurned = (index % course.width, index / course.width)
          }
        }
      }
      if let (column, row) = comparison.first ?? firstTurned {
        let index = row * course.width + column
        let (ray, hits) = probe(column, row)
        let courseFound = Self.nearest(hits, scene: scene)
        let fastFound = Self.fastFound(
          scene, ray: ray, t: fast.depth[index], normal: fast.normals[index])
        lines = Self.describe(
          column: column, row: row, ray: ray, course: courseFound,
          fast: fastFound)
      }
      if turned > 0 {
        lines.insert(
          "\(turned) pixels have normals more than 2.6° from the fast "
            + "engine's, which this image (|n|) may not show", at: 0)
      }
      outputs.append(
        Output(
          name: name, comparison: comparison, pixel: lines,
          turnedNormals: turned))
    }
  }

  /// The nearest of the course engine's hits, object by object.
  static func nearest(
    _ hits: [(index: Int, hit: Hit<Double>)], scene: Scene
  ) -> Found? {
    guard let best = hits.min(by: { $0.hit.t < $1.hit.t }) else { return nil }
    return Found(
      index: best.index, kind: scene.root.objects[best.index].kindName,
      materialIndex: best.hit.materialIndex, t: best.hit.t,
      normal: best.hit.normal)
  }

  /// The object the fast engine hit at depth `t`: of the scene's objects,
  /// the one whose own hit (each compiled alone by the fast engine,
  /// `CompiledScene.objectHits`) is nearest `t`; t and the normal are the
  /// render's own.
  static func fastFound(
    _ scene: Scene, ray: Ray<Double>, t: Double, normal: Vector3<Double>
  ) -> Found? {
    guard t.isFinite else { return nil }
    var best: (index: Int, distance: Double, material: Int)?
    for hit in CompiledScene<StableKernel<Double>>.objectHits(
      scene, direction: ray.direction)
    {
      let distance = abs(hit.t - t)
      if distance < (best?.distance ?? .infinity) {
        best = (hit.index, distance, hit.materialIndex)
      }
    }
    guard let best else { return nil }
    return Found(
      index: best.index, kind: scene.root.objects[best.index].kindName,
      materialIndex: best.material, t: t, normal: normal)
  }

  /// The pixel, its ray, what each engine hit, and what differs.
  static func describe(
    column: Int, row: Int, ray: Ray<Double>, course: Found?, fast: Found?
  ) -> [String] {
    func line(_ found: Found?) -> String {
      guard let found else { return "nothing (a miss)" }
      return "object \(found.index) of the group (\(found.kind), material "
        + "\(found.materialIndex)) at t = \(found.t), normal \(found.normal)"
    }
    var lines = [
      "first difference at column \(column), row \(row): the ray from "
        + "\(ray.origin) in direction \(ray.direction)",
      "  course engine hit \(line(course))",
      "  fast engine hit   \(line(fast))",
    ]
    lines.append("  so: " + verdict(course, fast))
    return lines
  }

  /// What the two hits say about the course's code.
  static func verdict(_ course: Found?, _ fast: Found?) -> String {
    switch (course, fast) {
    case (nil, nil):
      return "both engines' rays miss here, yet the pixels differ: the "
        + "course engine drew this pixel from another ray or another "
        + "background (see the pattern)"
    case (nil, let fast?):
      return "the course engine misses object \(fast.index) (\(fast.kind)), "
        + "which the fast engine hits: check its intersect"
    case (let course?, nil):
      return "the course engine hits object \(course.index) (\(course.kind)) "
        + "where the fast engine sees nothing: check its intersect"
    case (let course?, let fast?):
      if course.index != fast.index {
        return "they hit different objects (\(course.index) and "
          + "\(fast.index)): the nearest t is not kept, or a t is wrong"
      }
      let relative = abs(course.t - fast.t) / max(abs(fast.t), 1e-300)
      if relative > 1e-6 {
        return "the same object, but t differs by \(Float(relative)) "
          + "relative: check the intersection's formula (a sign, a root)"
      }
      let length = course.normal.length
      if abs(length - 1) > 1e-6 {
        return "the same object and t, but the course's normal has length "
          + "\(Float(length)), not 1: normalise it"
      }
      if course.normal.dot(fast.normal) < 0.999 {
        return "the same object and t, but the normals differ: check the "
          + "normal's direction (outward, and its transform)"
      }
      return "the same object, t and normal: the difference is in the "
        + "shading or in where the pixel is drawn"
    }
  }
}

extension EngineCheck {
  /// The pixels one engine hits and the other misses (depth finite in one
  /// buffer only), in order: never within a tolerance, so `--check` counts
  /// them, names the first and fails on any.
  package static func hitOrMissPixels(
    course: RenderBuffers<Double>, fast: RenderBuffers<Double>
  ) -> [Int] {
    precondition(course.depth.count == fast.depth.count)
    return course.depth.indices.filter {
      course.depth[$0].isFinite != fast.depth[$0].isFinite
    }
  }
}

extension EngineCheck {
  /// The cosine of the angle between two normals, whatever their lengths.
  static func cosine(_ a: Vector3<Double>, _ b: Vector3<Double>) -> Double {
    a.dot(b) / (a.length * b.length)
  }
}
