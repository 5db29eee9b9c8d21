import ArgumentParser
import enum Course.CourseEngine
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

extension Render {
  /// `--check`: first the course's shapes the scene uses, asked with rays
  /// whose answers are known (`ShapeProbes`), and nothing rendered when
  /// one fails; then each engine renders once, every buffer kept; the
  /// files given are written from the course engine's, and the two
  /// compared output by output.
  func checkEngines(_ scene: Scene, _ plan: Plan) throws {
    let png = try preflight(plan)
    let probes = ShapeProbes.check(scene)
    for line in probes.lines { printOutput(line) }
    if !probes.passes { throw ExitCode.failure }
    if !probes.lines.isEmpty { printOutput() }
    var request = plan.request
    let requested = plan.files.reduce(into: RenderOutputs()) {
      $0.formUnion($1.kind)
    }
    let compared: RenderOutputs =
      requested.isEmpty ? [.shaded, .normals, .depth] : requested
    // Depth and normals are always kept, for the report of the first
    // differing pixel; the shaded image only when it is compared (so that
    // `--check --depth d.png` needs no shading code: week 2's handout).
    request.settings.outputs = compared.union([.depth, .normals])
    request.settings.quantizedOutputs = []
    request.repeats = 0
    let textures: [Texture?]
    do {
      textures = try TextureLoader.load(for: scene)
    } catch {
      printError(error.report)
      throw ExitCode.failure
    }
    let settings = request.settings
    let (course, fast) = EngineRenders.render(
      scene, request: request, textures: textures)
    if !plan.files.isEmpty {
      do {
        try RenderJob.write(
          course, request: plan.request, files: plan.files,
          depthRange: plan.depthRange, png: png)
      } catch {
        printError("raytrace: error: \(error)")
        throw ExitCode.failure
      }
    }
    let check = EngineCheck(
      scene: scene, course: course, fast: fast, style: settings.style,
      outputs: compared,
      depthRange: plan.depthRange,
      tolerance: ImageComparison.defaultTolerance(eightBit: true)
    ) { column, row in
      CourseEngine.probe(scene, settings: settings, column: column, row: row)
    }
    let need = 0.999
    printOutput(
      "course engine against fast engine (\(request.fast.precision), "
        + "\(request.fast.method)), \(settings.width)×\(settings.height):")
    var failed = false
    for output in check.outputs {
      printOutput("\n\(output.name):")
      let names = ("course", "fast")
      for line in output.comparison.report(names.0, names.1, need: need)
        .dropFirst()
      {
        printOutput("  " + line)
      }
      for line in output.pixel { printOutput("  " + line) }
      if !output.passes(need: need) { failed = true }
    }
    // A pixel one engine hits and the other misses is never within a
    // tolerance: counted and placed, and the check fails on any.
    let width = settings.width
    let split = EngineCheck.hitOrMissPixels(course: course, fast: fast)
    if let first = split.first {
      let (row, column) = first.quotientAndRemainder(dividingBy: width)
      let courseHits = split.filter { course.depth[$0].isFinite }.count
      printOutput(
        "\nhit or miss: \(split.count) pixels where one engine hits and "
          + "the other misses (the course engine hits \(courseHits) of "
          + "them); the first at column \(column), row \(row)")
      failed = true
    }
    if failed { throw ExitCode.failure }
  }
}
