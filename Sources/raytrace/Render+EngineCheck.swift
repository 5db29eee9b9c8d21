import ArgumentParser
import enum Course.CourseEngine
import FastEngine
import Measurement
import SceneIO
import SceneModel

extension Render {
  /// `--check`: both engines in memory, compared output by output.
  func checkEngines(_ scene: Scene, _ plan: Plan) throws {
    var settings = plan.settings
    let requested = plan.files.reduce(into: RenderOutputs()) {
      $0.formUnion($1.kind)
    }
    // Every buffer is kept, for the report of the first differing pixel.
    settings.outputs = [.depth, .normals, .shaded]
    settings.quantizedOutputs = []
    settings.repeats = 0
    let textures: [Texture?]
    do {
      textures = try TextureLoader.load(for: scene)
    } catch {
      printError(error.description)
      throw ExitCode.failure
    }
    settings.engine = .course
    let course = CourseEngine.render(
      scene, textures: textures, settings: settings)
    settings.engine = .fast
    let fast = Self.fastBuffers(scene, textures: textures, settings: settings)
    let check = EngineCheck(
      scene: scene, course: course, fast: fast, style: settings.style,
      outputs: requested.isEmpty ? [.shaded, .normals, .depth] : requested,
      depthRange: plan.depthRange,
      tolerance: ImageComparison.defaultTolerance(eightBit: true)
    ) { column, row in
      CourseEngine.probe(scene, settings: settings, column: column, row: row)
    }
    let need = 0.999
    printOutput(
      "course engine against fast engine (\(settings.precision), "
        + "\(settings.method)), \(settings.width)×\(settings.height):")
    var failed = false
    for output in check.outputs {
      printOutput("\n\(output.name):")
      let names = ("course", "fast")
      for line in output.comparison.report(names.0, names.1, need: need).dropFirst()
      {
        printOutput("  " + line)
      }
      for line in output.pixel { printOutput("  " + line) }
      if !output.passes(need: need) { failed = true }
    }
    if failed { throw ExitCode.failure }
  }

  /// The fast engine's buffers in the render's precision and method, as
  /// Double.
  static func fastBuffers(
    _ scene: Scene, textures: [Texture?], settings: RenderSettings
  ) -> RenderBuffers<Double> {
    func render<Kernel: IntersectionKernel>(_: Kernel.Type)
      -> RenderBuffers<Double>
    {
      let buffers = Renderer.render(
        CompiledScene<Kernel>(scene, textures: textures), settings: settings)
      return RenderBuffers(
        width: buffers.width, height: buffers.height,
        depth: buffers.depth.map(Double.init),
        normals: buffers.normals.map(Vector3<Double>.init),
        color: buffers.color.map(Vector3<Double>.init))
    }
    switch (settings.precision, settings.method) {
    case (.double, .stable): return render(StableKernel<Double>.self)
    case (.double, .naive): return render(NaiveKernel<Double>.self)
    case (.float, .stable): return render(StableKernel<Float>.self)
    case (.float, .naive): return render(NaiveKernel<Float>.self)
    }
  }
}
