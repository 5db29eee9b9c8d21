import Dispatch
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport
import Course
import FastEngine
import FastKernels

/// One image file a render writes.
package struct OutputFile: Hashable, Sendable {
  /// Exactly one of `.depth`, `.normals`, `.shaded`.
  package var kind: RenderOutputs
  package var path: String
  package var format: ImageFormat

  /// Nil when the path's extension is not a known image format.
  package init?(kind: RenderOutputs, path: String) {
    guard let format = ImageFormat(path: path) else { return nil }
    self.kind = kind
    self.path = path
    self.format = format
  }
}

/// What a render did, for `--stats`.
package struct RenderReport: Sendable {
  package var request: RenderRequest
  package var settings: RenderSettings { request.settings }
  package var spheres: Int
  package var planes: Int
  /// How each pixel's nearest sphere was found; nil for the course
  /// engine, which tries every object of the group by the hit protocol.
  package var sphereSearch: Renderer.SphereSearch?
  package var usesHierarchy: Bool { sphereSearch == .hierarchy }
  package var triangles: Int = 0
  package var ellipsoids: Int = 0
  /// How each pixel's nearest triangle was found.
  package var triangleSearch = Renderer.TriangleSearch.everyTriangle
  package var compileSeconds: Double
  /// The render's time; with `settings.repeats`, the median of the
  /// repeated renders.
  package var renderSeconds: Double
  /// The first render's time: the one a single run waits for, with its
  /// buffers' first page faults and cold caches.
  package var firstRenderSeconds: Double = 0
  package var writeSeconds: Double
  /// Camera rays traced: one per pixel, plus `samples` more per pixel for
  /// supersampled shading; `samples` per pixel when every output is
  /// supersampled.
  package var rays: Int {
    let perPixel =
      settings.supersamplesAll
      ? settings.samples
      : settings.supersamples && settings.outputs.contains(.shaded)
        ? settings.samples + 1 : 1
    return settings.width * settings.height * perPixel
  }
  package var megaraysPerSecond: Double { Double(rays) / renderSeconds / 1e6 }
  /// The depth range a depth image used, if one was written.
  package var depthRange: ClosedRange<Double>?
  /// Materials with a texture, and the textures read for them (none unless
  /// a shaded image was rendered).
  package var texturedMaterials = 0
  package var texturesRead = 0

  /// What the requested outputs did not need, and so was not computed.
  package var leftOut: [String] {
    var parts: [String] = []
    let outputs = settings.outputs
    if !outputs.contains(.shaded) {
      parts.append("shading (lights, materials)")
    }
    if !outputs.needsNormals { parts.append("normals") }
    if !outputs.contains(.depth) { parts.append("depth buffer") }
    if texturedMaterials > 0 && texturesRead == 0 {
      parts.append("textures (not read: no shaded image)")
    }
    if planes == 0 { parts.append("plane tests (no planes)") }
    return parts
  }
}

/// A whole render: compile the scene for the chosen precision and method,
/// render the requested outputs, and write the files all or none
/// (`OutputBatch`, whose temporary files exist from before the render).
package enum RenderJob {
  /// Renders `scene` into `files`. Textures are read here, and only when a
  /// shaded image is among the files (a `SceneError` naming the texture
  /// when one cannot be read), unless `textures` gives them already.
  package static func run(
    scene: consuming Scene, request: RenderRequest, files: [OutputFile],
    depthRange: ClosedRange<Double>? = nil, png: PNGOptions = .default,
    textures given: [Texture?]? = nil,
    progress: (@Sendable (Int) -> Void)? = nil
  ) throws -> RenderReport {
    var request = request
    var settings = request.settings
    settings.outputs = files.reduce(into: []) { $0.formUnion($1.kind) }
    // Normals and colours that only 8-bit files show are rendered straight
    // into their pixels: no buffer of the render's precision for them.
    // (Depth keeps its values: its image's range comes from all of them.)
    for kind: RenderOutputs in [.normals, .shaded]
    where files.allSatisfy({ $0.kind != kind || $0.format.isEightBit }) {
      settings.quantizedOutputs.insert(kind)
    }
    request.settings = settings
    let textures =
      settings.outputs.contains(.shaded)
      ? try given ?? TextureLoader.load(for: scene) : []
    // Counted before the run, which lets the scene go (`runFast`).
    let texturedMaterials = scene.materials.count { $0.texturePath != nil }
    let texturesRead =
      Set(
        zip(scene.materials, textures).compactMap { material, texture in
          texture == nil ? nil : material.texturePath
        }
      ).count
    var report = try run(
      scene, textures, request, files, depthRange, png, progress)
    report.texturedMaterials = texturedMaterials
    report.texturesRead = texturesRead
    return report
  }

  private static func run(
    _ scene: consuming Scene, _ textures: [Texture?], _ request: RenderRequest,
    _ files: [OutputFile], _ depthRange: ClosedRange<Double>?,
    _ png: PNGOptions, _ progress: (@Sendable (Int) -> Void)?
  ) throws -> RenderReport {
    // The temporary files exist from here on, through the render: a
    // target that cannot be written fails now, and an interrupted render
    // leaves nothing behind.
    let batch = try OutputBatch(paths: files.map(\.path))
    let output = Output(
      request: request, files: files, depthRange: depthRange, png: png,
      batch: batch)
    switch request.engine {
    case .course:
      return try runCourse(scene, textures, output, progress)
    case .fast:
      return try runFast(scene, textures, output, progress)
    }
  }

  /// What to write once the buffers are rendered.
  private struct Output {
    var request: RenderRequest
    var settings: RenderSettings { request.settings }
    var files: [OutputFile]
    var depthRange: ClosedRange<Double>?
    var png: PNGOptions
    var batch: OutputBatch
  }

  /// The fast engine's render: compiled for the request's precision and
  /// method (`FastScene`), rendered, repeated, written.
  private static func runFast(
    _ scene: consuming Scene, _ textures: [Texture?], _ output: Output,
    _ progress: (@Sendable (Int) -> Void)?
  ) throws -> RenderReport {
    let settings = output.settings
    var clock = Stopwatch()
    let compiled = FastScene(
      copy scene, textures: textures, options: output.request.fast,
      thresholds: .render(supersampled: settings.supersamples),
      threads: settings.threads)
    // Compiled: the description is let go before the render (freed here
    // unless the caller keeps it; the 5·10⁶-triangle mesh's arrays are
    // 114 MiB).
    _ = consume scene
    let compileSeconds = clock.lap()
    let rendered = repeatedly(
      output.request.repeats, progress: progress, clock: &clock,
      empty: .double(RenderBuffers(width: 0, height: 0))
    ) {
      (
        progress: (@Sendable (Int) -> Void)?,
        recycled: consuming AnyRenderBuffers?
      ) -> Rendered<AnyRenderBuffers> in
      let result = compiled.render(
        settings, progress: progress, recycling: consume recycled)
      return (result.buffers, result.search, result.triangleSearch)
    }
    let counts = (
      compiled.spheres, compiled.planes, compiled.triangles,
      compiled.ellipsoids
    )
    // The compiled scene and the search it kept for repeats (8 bytes for
    // each triangle in each tile it touches) are let go before the files
    // are encoded, and the time that takes (unmapping them: 30 ms at
    // 5·10⁶ triangles) is left out of the write's, as when it was the
    // process's exit.
    _ = consume compiled
    _ = clock.lap()
    var report: RenderReport
    switch rendered.result.buffers {
    case .float(let buffers):
      report = try write(
        buffers, output, clock: &clock, search: rendered.result.search,
        seconds: rendered.seconds, compileSeconds: compileSeconds)
    case .double(let buffers):
      report = try write(
        buffers, output, clock: &clock, search: rendered.result.search,
        seconds: rendered.seconds, compileSeconds: compileSeconds)
    }
    (report.spheres, report.planes, report.triangles, report.ellipsoids) =
      counts
    report.triangleSearch = rendered.result.triangleSearch
    return report
  }

  /// The course engine's render (`CourseEngine`), written as the fast
  /// engine's is.
  private static func runCourse(
    _ scene: Scene, _ textures: [Texture?], _ output: Output,
    _ progress: (@Sendable (Int) -> Void)?
  ) throws -> RenderReport {
    var clock = Stopwatch()
    let rendered = repeatedly(
      output.request.repeats, progress: progress, clock: &clock,
      empty: RenderBuffers<Double>(width: 0, height: 0)
    ) { progress, _ in
      (
        CourseEngine.render(
          scene, textures: textures, settings: output.settings,
          progress: progress),
        nil, .everyTriangle
      )
    }
    var report = try write(
      rendered.result.buffers, output, clock: &clock, search: nil,
      seconds: rendered.seconds, compileSeconds: 0)
    let counts = scene.root.primitiveCounts
    report.spheres = counts.spheres
    report.planes = counts.planes
    report.triangles = counts.triangles
    report.ellipsoids = counts.ellipsoids
    return report
  }

  /// The first render (with `progress`), then `repeats` more: the last
  /// buffers, the first render's time and the median of the others'.
  ///
  /// Each repeat is handed the previous render's buffers to write over
  /// (`render`'s second argument; the fast engine reuses them), as a
  /// program that redraws an image keeps its memory: the first render's
  /// time includes faulting fresh buffers in, the repeats' do not.
  private static func repeatedly<Buffers>(
    _ repeats: Int, progress: (@Sendable (Int) -> Void)?,
    clock: inout Stopwatch, empty: Buffers,
    _ render:
      ((@Sendable (Int) -> Void)?, consuming Buffers?) -> Rendered<Buffers>
  ) -> (result: Rendered<Buffers>, seconds: (first: Double, median: Double)) {
    var result = render(progress, nil)
    let first = clock.lap()
    var repeated: [Double] = []
    for _ in 0..<repeats {
      let buffers = result.buffers
      result.buffers = empty
      _ = clock.lap()
      result = render(nil, consume buffers)
      repeated.append(clock.lap())
    }
    return (result, (first, repeated.isEmpty ? first : median(repeated)))
  }

  private typealias Rendered<Buffers> = (
    buffers: Buffers, search: Renderer.SphereSearch?,
    triangleSearch: Renderer.TriangleSearch
  )

  /// Writes `files` from buffers already rendered (`--check`'s course
  /// engine's), all or none, as `run` writes its own.
  package static func write(
    _ buffers: RenderBuffers<Double>, request: RenderRequest,
    files: [OutputFile], depthRange: ClosedRange<Double>? = nil,
    png: PNGOptions = .default
  ) throws {
    let output = Output(
      request: request, files: files, depthRange: depthRange, png: png,
      batch: try OutputBatch(paths: files.map(\.path)))
    var clock = Stopwatch()
    _ = try write(
      buffers, output, clock: &clock, search: nil,
      seconds: (0, 0), compileSeconds: 0)
  }

  /// Encodes and writes every file from `buffers`, and reports.
  private static func write<S: RayScalar>(
    _ buffers: RenderBuffers<S>, _ output: Output, clock: inout Stopwatch,
    search: Renderer.SphereSearch?, seconds: (first: Double, median: Double),
    compileSeconds: Double
  ) throws -> RenderReport {
    let (settings, files) = (output.settings, output.files)
    let usedRange =
      files.contains { $0.kind == .depth && $0.format.isEightBit }
      ? settings.style.depthRange(buffers.depth, given: output.depthRange)
      : nil
    let encoded = OutputEncoding.encode(
      buffers, files: files, style: settings.style, depthRange: usedRange,
      png: output.png, threads: settings.threads)
    try output.batch.commit(encoded)
    var report = RenderReport(
      request: output.request, spheres: 0, planes: 0, sphereSearch: search,
      compileSeconds: compileSeconds, renderSeconds: seconds.median,
      writeSeconds: clock.lap(), depthRange: usedRange)
    report.firstRenderSeconds = seconds.first
    return report
  }

  static func rawImage<S: RayScalar>(
    _ kind: RenderOutputs, _ buffers: RenderBuffers<S>
  ) -> RawImage<S> {
    let (width, height) = (buffers.width, buffers.height)
    switch kind {
    case .depth:
      return RawImage(
        width: width, height: height, channels: 1, values: buffers.depth)
    case .normals:
      return RawImage(
        width: width, height: height, channels: 3,
        values: flattened(buffers.normals) { ($0.x, $0.y, $0.z) })
    default:
      return RawImage(
        width: width, height: height, channels: 3,
        values: flattened(buffers.color) { ($0.x, $0.y, $0.z) })
    }
  }

  /// Each element's three values in a row, written into one new array.
  private static func flattened<Element, S>(
    _ elements: [Element], _ values: (Element) -> (S, S, S)
  ) -> [S] {
    [S](unsafeUninitializedCapacity: 3 * elements.count) { buffer, count in
      for (index, element) in elements.enumerated() {
        let (x, y, z) = values(element)
        (buffer.baseAddress! + 3 * index).initialize(to: x)
        (buffer.baseAddress! + 3 * index + 1).initialize(to: y)
        (buffer.baseAddress! + 3 * index + 2).initialize(to: z)
      }
      count = 3 * elements.count
    }
  }
}
