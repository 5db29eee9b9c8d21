import ArgumentParser

// Commands shaped like raytrace's, shared by the tests.

enum Finish: String, CaseIterable, ExpressibleByArgument {
  case matte, gloss
}

enum Precision: String, CaseIterable, ExpressibleByArgument {
  case float, double
}

/// The option shapes of `raytrace render`, including the assignment's
/// single-dash spellings.
struct RenderLike: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "render", abstract: "Render a scene.")

  @Argument(help: "The scene file.")
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
    help: ArgumentHelp("Image width and height in pixels.", valueName: "w h"))
  var size: [Int] = []

  @Option(
    name: .long,
    help: ArgumentHelp("Write the depth image to this file.", valueName: "file")
  )
  var depth: String?

  @Option(
    name: .customLong("depth", withSingleDash: true), parsing: .upToNextOption,
    help: ArgumentHelp("Range and file.", valueName: "min max file"))
  var assignmentDepth: [String] = []

  @Option(
    name: .customLong("depth-range"), parsing: .upToNextOption,
    help: ArgumentHelp("Map depths MIN..MAX.", valueName: "min max"))
  var depthRange: [Double] = []

  @Option(help: "Precision of the geometry.")
  var precision: Precision = .double

  @Option(help: "Worker threads.")
  var threads: Int?

  @Option(help: "Horizontal shift in pixels.")
  var shift: Int = 0

  @Option(name: .customLong("png-level"), help: "zlib level.")
  var pngLevel: Int = 6

  @Flag(help: "Print statistics.")
  var stats = false

  mutating func validate() throws {
    if scene != nil, input != nil {
      throw ValidationError(
        "Give the scene either as an argument or with -input, not both.")
    }
  }

  func run() throws {}
}

/// A small command whose help text the tests compare whole.
struct Paint: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "paint",
    abstract: "Paint a scene.",
    discussion: "Reads the scene and writes an image.")

  @Argument(help: "The scene file.")
  var scene: String

  @Option(
    name: [
      .customShort("o"), .long, .customLong("output", withSingleDash: true),
    ],
    help: ArgumentHelp("Write the image to this file.", valueName: "file"))
  var output: String?

  @Option(
    name: [.long, .customLong("size", withSingleDash: true)],
    parsing: .upToNextOption,
    help: ArgumentHelp("Width and height.", valueName: "w h"))
  var size: [Int] = []

  @Option(help: "The surface finish.")
  var finish: Finish = .matte

  @Option(
    help:
      "zlib level for PNG files, 0 to 9: lower is faster and larger, higher smaller and slower."
  )
  var pngLevel: Int = 6

  @Flag(help: "Print statistics.")
  var stats = false

  mutating func validate() throws {
    guard size.isEmpty || size.count == 2 else {
      throw ValidationError(
        "--size takes two values, W and H; got \(size.count).")
    }
  }
}

struct Report: ParsableCommand {
  static let configuration = CommandConfiguration(abstract: "Measure things.")

  @Argument(help: "Scene files.")
  var scenes: [String] = []

  @Option(help: "Timed renders per row.")
  var runs = 5

  func run() throws {
    throw ValidationError("Report failed on purpose.")
  }
}

struct Bench: ParsableCommand {
  static let configuration = CommandConfiguration(
    abstract: "Time things.", shouldDisplay: false)
}

/// Dispatches to `paint` by default, like `raytrace` to `render`.
struct Draw: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "draw",
    abstract: "Draw things.",
    subcommands: [Paint.self, Report.self, Bench.self],
    defaultSubcommand: Paint.self)
}

/// Subcommands without a default, and a version.
struct Tools: ParsableCommand {
  static let configuration = CommandConfiguration(
    version: "1.2.3", subcommands: [Report.self])
}
