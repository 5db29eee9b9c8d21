import Dispatch
import ArgumentParser
import enum Course.CourseEngine
import enum Course.CourseShapes
import FastEngine
import FastKernels
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

struct Render: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "render",
    abstract: "Render a scene file (the default command).",
    discussion: """
      Each output's format comes from its extension: .png (8-bit RGB), .ppm \
      (binary P6), .pfm (32-bit float: raw t with +inf for a miss, or raw \
      normals with 0 0 0 for a miss) or .npy (the same raw values in the \
      render's precision). At least one output is required.

      The original assignment's command line is accepted as is and implies \
      --style mit:
        raytrace -input SCENE -size W H [-output FILE] [-normals FILE]
                 [-depth MIN MAX FILE]
      """)

  @Argument(
    help: "The scene file: the course's text format or a property list.")
  var scene: String?

  @Option(
    name: .customLong("input", withSingleDash: true),
    help: ArgumentHelp(
      "The scene file (the assignment's spelling).", valueName: "scene"))
  var input: String?

  @Option(
    name: [
      .customShort("o"), .long, .customLong("output", withSingleDash: true),
    ],
    help: ArgumentHelp(
      "Write the shaded image to this file.", valueName: "file"))
  var output: String?

  @Option(
    name: [.long, .customLong("size", withSingleDash: true)],
    parsing: .upToNextOption,
    help: ArgumentHelp(
      "Image width and height in pixels (default: 800 800).", valueName: "w h"))
  var size: [Int] = []

  @Option(
    name: .long,
    help: ArgumentHelp("Write the depth image to this file.", valueName: "file")
  )
  var depth: String?

  @Option(
    name: .customLong("depth", withSingleDash: true), parsing: .upToNextOption,
    help: ArgumentHelp(
      "The assignment's depth option: range and file (mit style).",
      valueName: "min max file"))
  var assignmentDepth: [String] = []

  @Option(
    name: .customLong("depth-range"), parsing: .upToNextOption,
    help: ArgumentHelp(
      """
      Map depths MIN..MAX to the depth image (default: the course style \
      takes the nearest to the farthest hit closer than 40; the mit style \
      the nearest to the farthest hit).
      """,
      valueName: "min max"))
  var depthRange: [Double] = []

  @Option(
    name: [.long, .customLong("normals", withSingleDash: true)],
    help: ArgumentHelp(
      "Write the normals image to this file.", valueName: "file"))
  var normals: String?

  @Option(
    help: ArgumentHelp(
      """
      Image convention: course (the Swift course's images) or mit (the \
      original assignment's; the default with -input).
      """,
      valueName: "style"))
  var style: ImageStyle?

  @Option(
    help:
      """
      The fast engine's precision: double (the default) is exact to a few \
      ulps on every scene of the stiff suite; float is faster but loses \
      planets and far-from-origin scenes. Float implies --engine fast.
      """
  )
  var precision: Precision?

  @Option(
    help:
      """
      The fast engine's sphere intersection: stable (cancellation-free, \
      the default) or naive (the textbook formula, for comparison). Naive \
      implies --engine fast.
      """
  )
  var intersection: IntersectionMethod?

  @Option(
    help: ArgumentHelp(
      """
      Renderer: course (the default: the course's loop over every object \
      by the hit protocol, Sources/Course) or fast (the same scene within \
      a stated bound, much faster in a release build, exact for spheres \
      and planes at any scale).
      """,
      valueName: "engine"))
  var engine: Engine?

  @Option(
    help:
      """
      Worker threads (default: all cores). The image is identical for any \
      count.
      """
  )
  var threads: Int?

  @Option(
    name: .customLong("png-level"),
    help:
      """
      zlib level for PNG files, 0 to 9: lower is faster and larger, higher \
      smaller and slower.
      """
  )
  var pngLevel: Int = Int(PNGOptions.default.compressionLevel)

  @Option(
    help: ArgumentHelp(
      """
      Rays per pixel for the shaded image: 1, 4, 9, 16, ... (a square), \
      jittered on a grid of strata; depth and normals keep the pixel \
      centre unless --sample-all-outputs.
      """,
      valueName: "n"))
  var samples: Int = 1

  @Option(
    name: [.long, .customLong("filter", withSingleDash: true)],
    help:
      """
      The pixel filter of supersampled shading: box (the pixel's square) or \
      tent (a 2x2-pixel tent).
      """
  )
  var filter: PixelFilter = .box

  @Flag(
    name: .customLong("sample-all-outputs"),
    help:
      """
      Depth and normals too are the means of the --samples rays of each \
      pixel: depth over the rays that hit, normals with a miss as zero. \
      Without a shaded image nothing is shaded.
      """
  )
  var sampleAllOutputs = false

  @Flag(
    name: .customLong("jitter", withSingleDash: true),
    help:
      """
      The assignment's spelling: samples are always jittered, so this \
      changes nothing.
      """
  )
  var jitter = false

  @Flag(
    help:
      """
      Print what was rendered to standard error: size, rays, time, \
      throughput, and which outputs were computed or left out.
      """
  )
  var stats = false

  @Flag(
    help:
      """
      Render with the course engine and with the fast engine, and report \
      per output (all three when none is given) how far they differ, and \
      what each engine hit at the first pixel where they do. The outputs \
      given are written from the course engine. Exit status 1 when an \
      output differs on more than 0.1 % of its pixels.
      """
  )
  var check = false

  // Unconditional: a negative count reaches validate() and its message.
  @Option(
    name: .customLong("repeat"), parsing: .unconditional,
    help: ArgumentHelp(
      """
      Render the image N more times in the same process; --stats then \
      reports the median of those warm renders, and the first one's time \
      (for benchmarks: peers time repeated renders). The files are written \
      once.
      """,
      valueName: "n"))
  var repeats = 0

  func run() throws {
    // Before anything is written or rendered: a terminating signal then
    // removes the temporary outputs, whenever it comes.
    AtomicFile.installInterruptCleanup()
    let plan = try plan()
    // The machine's limit, not a mistake in the command line: one line,
    // status 1, before anything is read or allocated.
    if let problem = Self.memoryLimitProblem(
      width: plan.settings.width, height: plan.settings.height,
      files: plan.files)
    {
      printError("raytrace: error: \(problem)")
      throw ExitCode.failure
    }
    // Starts a dispatch worker thread while the scene is read, so that the
    // render's second thread is running when it is handed rows: created on
    // demand, it sometimes started 2–4 ms late, a third of a small render.
    if plan.settings.threads > 1 {
      DispatchQueue.global().async {}
    }
    let scene: Scene
    var clock = Stopwatch()
    do {
      scene = try SceneReader.read(
        contentsOf: plan.scenePath,
        options: SceneOptions(
          style: plan.settings.style,
          precision: plan.request.fast.precision.numberRange,
          shapes: CourseShapes.all, threads: plan.settings.threads))
    } catch {
      printError(error.report)
      throw ExitCode.failure
    }
    let parseSeconds = clock.lap()
    // What the engines that render cannot hold: the fast engine at any
    // scale it traces at, the course engine at the scene's own lengths.
    // Where the course engine cannot, the fast engine's verdict (in
    // double, the course engine's precision) decides whether it is the
    // remedy.
    let usesFast = plan.request.engine == .fast || check
    let usesCourse = plan.request.engine == .course || check
    let precision = plan.request.fast.precision
    let fastProblem = {
      LengthScale.problem(
        scene, precision: precision, threads: plan.settings.threads
      ).map { ($0, precision.remedy) }
    }
    let problem: (String, Remedy?)? =
      (usesFast ? fastProblem() : nil)
      ?? (usesCourse
        ? CourseEngineLimits.problem(scene).map {
          fastProblem() ?? ($0, .fastEngine)
        } : nil)
    if let (message, remedy) = problem {
      printError(
        SceneError(
          file: plan.scenePath, line: 0, column: 0, message: message
        ).report(remedy: remedy))
      throw ExitCode.failure
    }
    try checkOutputs(plan.files, against: scene)
    if check {
      try checkEngines(scene, plan)
      return
    }
    try render(consume scene, plan, parseSeconds: parseSeconds)
  }

  nonisolated(unsafe) private static var keptUntilExit: Scene?

  /// Writes the plan's files from the chosen engine.
  private func render(
    _ scene: consuming Scene, _ plan: Plan, parseSeconds: Double
  ) throws {
    let png = try preflight(plan)
    let report: RenderReport
    do {
      let bar = ProgressBar(rows: plan.settings.height)
      defer { bar?.finish() }
      // The default engine, on a scene it will be slow on, says so early.
      let note =
        engine == nil && plan.request.engine == .course
        ? SlowRenderNote(
          rows: plan.settings.height, limit: Self.slowCourseRender) : nil
      var progress: (@Sendable (Int) -> Void)?
      if bar != nil || note != nil {
        progress = { finished in
          note?.update(finished) { bar?.finish() }
          bar?.update(finished)
        }
      }
      // Handed over, the fast engine's render frees the scene once it is
      // compiled (a mesh's arrays not held through the render). A scene
      // of many objects is kept until the process exits instead, which
      // takes their memory back at once: freed one by one, 10⁶ spheres
      // took 30 ms.
      if scene.root.objects.count > 10_000 { Self.keptUntilExit = copy scene }
      report = try RenderJob.run(
        scene: consume scene, request: plan.request, files: plan.files,
        depthRange: plan.depthRange, png: png, progress: progress)
    } catch let error as SceneError {
      // A texture that cannot be read, named as a scene error is.
      printError(error.report)
      throw ExitCode.failure
    } catch {
      printError("raytrace: error: \(error)")
      throw ExitCode.failure
    }
    if stats {
      printStats(report, scenePath: plan.scenePath, parseSeconds: parseSeconds)
    }
    if engine == nil, plan.request.engine == .course,
      report.firstRenderSeconds > Self.slowCourseRender
    {
      printError(
        "raytrace: note: the course engine took "
          + "\(formatted(report.firstRenderSeconds)) s; --engine fast renders "
          + "the same scene in a fraction of that.")
    }
  }

  /// Before a render: every file's folder writable and room for the
  /// files (one line and exit 1 otherwise); the PNG options to write with.
  func preflight(_ plan: Plan) throws -> PNGOptions {
    do {
      for file in plan.files {
        try AtomicFile.checkWritable(file.path)
      }
    } catch {
      printError("raytrace: error: \(error)")
      throw ExitCode.failure
    }
    if let problem = Self.roomProblem(plan) {
      printError("raytrace: error: \(problem)")
      throw ExitCode.failure
    }
    var png = PNGOptions.default
    png.compressionLevel = Int32(pngLevel)
    return png
  }

  /// Seconds of a default render after which the fast engine is named.
  static let slowCourseRender = 2.0

  private func formatted(_ seconds: Double) -> String {
    String(Double((seconds * 10).rounded()) / 10)
  }

}
