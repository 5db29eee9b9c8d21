import ArgumentParser
import enum Course.CourseShapes
import FastEngine
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// `raytrace report`: error against run time for every precision and method.
struct Report: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "report",
    abstract:
      """
        Measure the fast engine's precisions and intersection methods \
        against a high-precision reference.
        """,
    discussion: """
      Renders every scene with the fast engine (the one with a choice of \
      precision and method) in float and double, naive and stable, times each \
      (the fastest of --rounds medians of --runs renders after a warm-up, \
      naive and stable in alternation, and stable's time over naive's in the \
      same precision), compares depth and normals \
      with the reference path (the same camera rays intersected in 80-bit \
      extended precision on x86, in double-double elsewhere; see \
      --reference) and prints a Markdown table. Relative errors are \
      |t − t_ref| / t_ref; ε is 2^-23 for float and 2^-52 for double.
      """)

  @Argument(
    help:
      """
        Scene files (default: scenes/stiff/*.txt and the course-like scenes \
        in scenes/).
        """
  )
  var scenes: [String] = []

  @Option(
    parsing: .upToNextOption,
    help: ArgumentHelp("Image width and height.", valueName: "w h"))
  var size: [Int] = [400, 400]

  @Option(help: "Timed renders per round and row, after one warm-up.")
  var runs: Int = 5

  @Option(
    help: """
      Rounds of --runs renders, the methods in alternation; a row's time \
      is its fastest round's median.
      """)
  var rounds: Int = 3

  @Option(help: "Worker threads for the timed renders (default: all cores).")
  var threads: Int?

  @Option(
    help: ArgumentHelp(
      "Also write the rows as CSV to this file.", valueName: "file"))
  var csv: String?

  @Option(
    help: ArgumentHelp(
      "Write one PNG per row with the per-pixel error of t in false colour.",
      valueName: "dir"))
  var heatmaps: String?

  @Option(
    help: ArgumentHelp(
      "The reference's precision: float80 (x86 only, the default there) "
        + "or double-double (the default elsewhere).",
      valueName: "precision"))
  var reference: ReferencePrecision = .platformDefault

  @Flag(
    help:
      """
        Leave out the antialiasing rows (shaded image, 1 to 64 samples \
        against 1024).
        """
  )
  var skipAntialiasing = false

  private var antialiasingHeader: String {
    """
    | scene | size | samples | time (ms) | RMS error vs 1024 samples \
    | max error (levels) |
    |---|---|---:|---:|---:|---:|
    """
  }

  static let defaultScenes = [
    "scenes/spheres.txt", "scenes/spheres-only.txt", "scenes/single-sphere.txt",
  ]

  mutating func validate() throws {
    guard !Raytrace.defersValidation else { return }
    guard size.count == 2, size.allSatisfy({ (1...4096).contains($0) }) else {
      throw ValidationError("--size takes two values between 1 and 4096.")
    }
    guard runs >= 1 else { throw ValidationError("--runs must be at least 1.") }
    guard rounds >= 1 else {
      throw ValidationError("--rounds must be at least 1.")
    }
    if let threads, threads < 1 {
      throw ValidationError("--threads must be at least 1.")
    }
    guard reference.isAvailable else {
      throw ValidationError(
        "--reference float80 needs an x86 processor; use double-double.")
    }
  }

  func run() throws {
    let paths = scenes.isEmpty ? try defaultScenePaths() : scenes
    let (width, height) = (size[0], size[1])
    let threads = threads ?? Platform.availableCores
    var rows: [AccuracyRow] = []
    var encodedMaps: [(bytes: [UInt8], path: String)] = []
    if let heatmaps {
      try checkOutputFolder(heatmaps)
    }
    if let csv {
      // Never over what this run reads.
      for path in paths where FileIdentity.same(csv, path) {
        throw ValidationError(
          "--csv '\(SceneParser.escaped(csv))' would overwrite the scene "
            + "file '\(SceneParser.escaped(path))'.")
      }
      try checked { () throws(OutputError) in try AtomicFile.checkWritable(csv)
      }
    }
    let names = Self.distinctNames(paths.map(sceneName))
    printOutput(AccuracyRow.markdownHeader)
    for (path, name) in zip(paths, names) {
      let scene: Scene
      do {
        // Either format, by content, as `render` reads it.
        scene = try SceneReader.read(
          contentsOf: path,
          options: SceneOptions(style: .course, shapes: CourseShapes.all))
      } catch {
        printError(error.report)
        throw ExitCode.failure
      }
      for precision in Precision.allCases {
        // A scene whose numbers the precision cannot hold (the stiff
        // suite's double-only scenes) has no row in it: the renderer
        // refuses it.
        if precision != .double {
          let options = SceneOptions(
            style: .course, precision: precision, shapes: CourseShapes.all)
          guard
            (try? SceneReader.read(contentsOf: path, options: options)) != nil
          else { continue }
        }
        // Generic over the reference's scalar, chosen by --reference.
        func measureRows<R: RayScalar>(against reference: RenderBuffers<R>) {
          let renders = AccuracyRender.renderMethods(
            scene, width: width, height: height, precision: precision,
            threads: threads, runs: runs, rounds: rounds)
          let naiveSeconds =
            renders.first { $0.method == .naive }?.seconds ?? .nan
          for (method, buffers, seconds) in renders {
            let measurement = buffers.measured(against: reference)
            let row = AccuracyRow(
              scene: name, precision: precision, method: method,
              width: width, height: height, seconds: seconds,
              naiveSeconds: naiveSeconds, measurement: measurement,
              epsilon: buffers.epsilon)
            printOutput(row.markdown)
            rows.append(row)
            if let heatmaps {
              let image = ErrorHeatmap.image(
                measurement, width: width, height: height,
                epsilon: buffers.epsilon)
              encodedMaps.append(
                (
                  PNGEncoder.encode(image),
                  "\(heatmaps)/\(name)-\(precision.rawValue)-"
                    + "\(method.rawValue).png"
                ))
            }
          }
        }
        func referenceBuffers<R: RayScalar>(
          in _: R.Type
        ) -> RenderBuffers<R> {
          AccuracyRender.reference(
            scene, width: width, height: height, rays: precision,
            threads: threads, in: R.self)
        }
        switch reference {
        case .doubleDouble:
          measureRows(against: referenceBuffers(in: DoubleDouble.self))
        case .float80:
          #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
            measureRows(against: referenceBuffers(in: Float80.self))
          #else
            preconditionFailure("refused by validate()")
          #endif
        }
      }
    }
    if !skipAntialiasing {
      printOutput()
      printOutput(antialiasingHeader)
      for path in scenes.isEmpty ? Self.defaultScenes : paths {
        let scene: Scene
        do {
          // Either format, by content, as `render` reads it.
        scene = try SceneReader.read(
          contentsOf: path,
          options: SceneOptions(style: .course, shapes: CourseShapes.all))
        } catch {
          printError(error.report)
          throw ExitCode.failure
        }
        // Half the size: the 1024-sample reference is a thousand renders.
        let (w, h) = (max(1, width / 2), max(1, height / 2))
        let (reference, _) = AntialiasingMeasurement.render(
          scene, width: w, height: h, samples: 1024, threads: threads, runs: 0)
        for samples in [1, 4, 16, 64] {
          let (color, seconds) = AntialiasingMeasurement.render(
            scene, width: w, height: h, samples: samples, threads: threads,
            runs: runs)
          let m = AntialiasingMeasurement(color, against: reference)
          printOutput(
            "| \(sceneName(path)) | \(w)×\(h) | \(samples) | "
              + "\(formatted(seconds * 1000, digits: 3)) | "
              + "\(scientific(m.rootMeanSquare)) | "
              + "\(formatted(m.maxLevels, digits: 3)) |"
          )
        }
      }
    }
    if let csv {
      let text =
        ([AccuracyRow.csvHeader] + rows.map(\.csv)).joined(separator: "\n")
        + "\n"
      try checked { () throws(OutputError) in
        try AtomicFile.write(Array(text.utf8), to: csv)
      }
    }
    // Each heatmap is a file of its own, whole or absent.
    for map in encodedMaps {
      try checked { () throws(OutputError) in
        try AtomicFile.write(map.bytes, to: map.path)
      }
    }
  }

  /// The stiff suite and the course-like scenes, from the project's root.
  private func defaultScenePaths() throws -> [String] {
    let stiff = listTextFiles(in: "scenes/stiff")
    guard !stiff.isEmpty else {
      throw ValidationError(
        "No scenes given and scenes/stiff/ not found: run from the project's "
          + "root or name the scenes."
      )
    }
    return stiff + Self.defaultScenes
  }

  /// The names, those that repeat numbered in order (`scene`, `scene-2`,
  /// …), so that two scenes of one name in different folders give two
  /// rows and two heatmaps that can be told apart.
  static func distinctNames(_ names: [String]) -> [String] {
    var seen: [String: Int] = [:]
    return names.map { name in
      seen[name, default: 0] += 1
      let count = seen[name] ?? 1
      return count == 1 ? name : "\(name)-\(count)"
    }
  }

  private func sceneName(_ path: String) -> String {
    var name = path.split(separator: "/").last.map(String.init) ?? path
    if name.hasSuffix(".txt") { name.removeLast(4) }
    return name
  }

  /// Creates the folder when it does not exist yet (its parent must), then
  /// checks that files can be written in it.
  private func checkOutputFolder(_ folder: String) throws {
    mkdir(folder, 0o755)
    try checked { () throws(OutputError) in
      try AtomicFile.checkWritable(folder + "/.probe")
    }
  }

  private func checked(_ body: () throws(OutputError) -> Void) throws {
    do {
      try body()
    } catch {
      printError("raytrace: error: \(error)")
      throw ExitCode.failure
    }
  }
}

/// One row of the report.
struct AccuracyRow {
  var scene: String
  var precision: Precision
  var method: IntersectionMethod
  var width: Int
  var height: Int
  var seconds: Double
  /// The naive method's time for the same scene and precision.
  var naiveSeconds: Double
  var measurement: AccuracyMeasurement
  var epsilon: Double

  var megaraysPerSecond: Double { Double(width * height) / seconds / 1e6 }
  var timeOverNaive: Double { seconds / naiveSeconds }

  static let markdownHeader = """
    | scene | precision | method | time (ms) | ÷ naive | Mrays/s \
    | max rel. error of t | p99 | max (ε) | max off silhouettes (ε) \
    | hit/miss disagreements | max normal error (°) |
    |---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|
    """

  var markdown: String {
    let m = measurement
    return "| \(scene) | \(precision.rawValue) | \(method.rawValue) | "
      + "\(formatted(seconds * 1000, digits: 3)) | "
      + "\(formatted(timeOverNaive, digits: 3)) | "
      + "\(formatted(megaraysPerSecond, digits: 3)) | "
      + "\(scientific(m.maxRelativeError)) | \(scientific(m.p99RelativeError)) "
      + "| "
      + "\(scientific(m.maxRelativeError / epsilon)) | "
      + "\(scientific(m.maxInteriorRelativeError / epsilon)) | "
      + "\(m.disagreements) | "
      + "\(scientific(m.maxNormalErrorDegrees)) |"
  }

  static let csvHeader =
    "scene,precision,method,width,height,seconds,time_over_naive,"
    + "mrays_per_s,max_rel_error,"
    + "p99_rel_error,max_rel_error_eps,max_interior_rel_error_eps,"
    + "disagreements,compared_hits,max_normal_error_deg"

  var csv: String {
    let m = measurement
    return [
      scene, precision.rawValue, method.rawValue, "\(width)", "\(height)",
      "\(seconds)", "\(timeOverNaive)",
      "\(megaraysPerSecond)", "\(m.maxRelativeError)", "\(m.p99RelativeError)",
      "\(m.maxRelativeError / epsilon)",
      "\(m.maxInteriorRelativeError / epsilon)",
      "\(m.disagreements)", "\(m.comparedHits)",
      "\(m.maxNormalErrorDegrees)",
    ].joined(separator: ",")
  }
}
