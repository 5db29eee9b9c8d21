import ArgumentParser
import enum Course.CourseShapes
import FastEngine
import FastKernels
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
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
  var runs: Int = 11

  @Option(
    help: """
      Rounds of --runs renders, the methods in alternation; a row's time \
      is its fastest round's median.
      """)
  var rounds: Int = 3

  @Option(
    help: """
      Worker threads for the timed renders (default: 1; more threads add \
      their start and join to renders of a few milliseconds).
      """)
  var threads: Int = 1

  @Option(
    help: ArgumentHelp(
      "Also draw error against run time (and antialiasing) as an SVG file.",
      valueName: "file.svg"))
  var plot: String?

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
    if threads < 1 {
      throw ValidationError("--threads must be at least 1.")
    }
    guard reference.isAvailable else {
      throw ValidationError(
        "--reference float80 needs an x86 processor; use double-double.")
    }
  }

  func run() throws {
    let paths = scenes.isEmpty ? try defaultScenePaths() : scenes
    if !BuildKind.isOptimized {
      printError(
        "raytrace: warning: a debug build: its times are not representative "
          + "(the fast engine runs unoptimised); time with `swift build -c "
          + "release` and .build/release/raytrace report")
    }
    let timing = AccuracyRow.Timing(
      width: size[0], height: size[1], threads: threads, runs: runs,
      rounds: rounds)
    if let heatmaps {
      try checkOutputFolder(heatmaps)
    }
    for (option, file) in [("--csv", csv), ("--plot", plot)] {
      guard let file else { continue }
      // Never over what this run reads.
      for path in paths where FileIdentity.same(file, path) {
        throw ValidationError(
          "\(option) '\(SceneParser.escaped(file))' would overwrite the "
            + "scene file '\(SceneParser.escaped(path))'.")
      }
      try checked { () throws(OutputError) in
        try AtomicFile.checkWritable(file)
      }
    }
    var rows: [AccuracyRow] = []
    var encodedMaps: [(bytes: [UInt8], path: String)] = []
    let names = Self.distinctNames(paths.map(sceneName))
    printOutput(AccuracyRow.markdownHeader)
    for (path, name) in zip(paths, names) {
      let scene = try read(path)
      for precision in Precision.allCases {
        // A scene whose numbers the precision cannot hold (the stiff
        // suite's double-only scenes) has no row in it: the renderer
        // refuses it.
        if precision != .double {
          let options = SceneOptions(
            style: .course, precision: precision.numberRange,
            shapes: CourseShapes.all)
          guard
            (try? SceneReader.read(contentsOf: path, options: options)) != nil
          else { continue }
        }
        for row in AccuracyRow.measure(
          scene, name: name, precision: precision, reference: reference,
          timing: timing)
        {
          printOutput(row.markdown)
          rows.append(row)
          if let heatmaps {
            let image = ErrorHeatmap.image(
              row.measurement, width: row.width, height: row.height,
              epsilon: row.epsilon)
            encodedMaps.append(
              (
                PNGEncoder.encode(image),
                "\(heatmaps)/\(name)-\(precision.rawValue)-"
                  + "\(row.method.name).png"
              ))
          }
        }
      }
    }
    var antialiasing: [AntialiasingRow] = []
    if !skipAntialiasing {
      printOutput()
      printOutput(AntialiasingRow.markdownHeader)
      for path in scenes.isEmpty ? Self.defaultScenes : paths {
        // Half the size: the 1024-sample reference is a thousand renders.
        let more = AntialiasingRow.measure(
          try read(path), name: sceneName(path), width: max(1, size[0] / 2),
          height: max(1, size[1] / 2), threads: threads, runs: runs)
        for row in more { printOutput(row.markdown) }
        antialiasing += more
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
    if let plot {
      let svg = ErrorPlot.svg(rows: rows, antialiasing: antialiasing)
      try checked { () throws(OutputError) in
        try AtomicFile.write(Array(svg.utf8), to: plot)
      }
    }
    // Each heatmap is a file of its own, whole or absent.
    for map in encodedMaps {
      try checked { () throws(OutputError) in
        try AtomicFile.write(map.bytes, to: map.path)
      }
    }
  }

  /// The scene at `path`, in either format by content, as `render` reads
  /// it; its error printed and the command failed when it cannot be read.
  private func read(_ path: String) throws -> Scene {
    do {
      return try SceneReader.read(
        contentsOf: path,
        options: SceneOptions(style: .course, shapes: CourseShapes.all))
    } catch {
      printError(error.report)
      throw ExitCode.failure
    }
  }

  /// The stiff suite and the course-like scenes, from the project's root.
  private func defaultScenePaths() throws -> [String] {
    let stiff = Platform.names(in: "scenes/stiff")
      .filter { $0.hasSuffix(".txt") }.map { "scenes/stiff/" + $0 }
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

/// The report's rows as the table and the CSV print them.
extension AccuracyRow {
  static let markdownHeader = """
    | scene | precision | method | time (ms) | ÷ naive | Mrays/s \
    | max rel. error of t | p99 | max (ε) | max off silhouettes (ε) \
    | hit/miss disagreements | max normal error (°) |
    |---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|
    """

  var markdown: String {
    let m = measurement
    let label = method == .course ? "course engine" : method.name
    return "| \(scene) | \(precision.rawValue) | \(label) | "
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
      scene, precision.rawValue, method.name, "\(width)", "\(height)",
      "\(seconds)", "\(timeOverNaive)",
      "\(megaraysPerSecond)", "\(m.maxRelativeError)", "\(m.p99RelativeError)",
      "\(m.maxRelativeError / epsilon)",
      "\(m.maxInteriorRelativeError / epsilon)",
      "\(m.disagreements)", "\(m.comparedHits)",
      "\(m.maxNormalErrorDegrees)",
    ].joined(separator: ",")
  }
}

extension AntialiasingRow {
  static let markdownHeader = """
    | scene | size | samples | time (ms) | RMS error vs 1024 samples \
    | max error (levels) |
    |---|---|---:|---:|---:|---:|
    """

  var markdown: String {
    "| \(scene) | \(width)×\(height) | \(samples) | "
      + "\(formatted(seconds * 1000, digits: 3)) | "
      + "\(scientific(measurement.rootMeanSquare)) | "
      + "\(formatted(measurement.maxLevels, digits: 3)) |"
  }
}
