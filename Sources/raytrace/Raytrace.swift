import ArgumentParser
import FastEngine
import FastKernels
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

@main
struct Raytrace: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "raytrace",
    abstract:
      "Ray-cast a scene into shaded, depth and normal images.",
    discussion: """
      To render a scene (the render command is the default):
        raytrace SCENE -o out.png [--depth depth.png] [--normals normals.png]
        raytrace -input SCENE -size W H -output out.png   (the assignment's)

      A scene is a file in the course's text format or a property list of \
      the Swift course (XML or binary), told apart by content. Its objects: \
      Sphere, Plane, Triangle, TriangleMesh (an OBJ file, optionally \
      textured), Group, and Transform (translate, scale, rotate, matrix) \
      around any of them; a PerspectiveCamera, point and directional \
      lights, Phong materials.

      The default engine is the course's code (Sources/Course); \
      --engine fast renders the same scene with the fast engine.
      """,
    subcommands: [Render.self, Compare.self, Report.self, Bench.self],
    defaultSubcommand: Render.self)

  /// Whether the commands' `validate()` checks nothing: the first of the
  /// two parses of `parseCommand(_:)`.
  @TaskLocal static var defersValidation = false

  /// The entry point: `main()` of the argument parser, with the command line
  /// read by `parseCommand(_:)`.
  static func main() {
    Platform.keepFreedMemory()
    do {
      var command = try parseCommand(Array(CommandLine.arguments.dropFirst()))
      try command.run()
    } catch {
      reportOutputFailure()
      exit(withError: error)
    }
    reportOutputFailure()
  }

  /// A write to standard output that failed (a full device, a closed
  /// file) is an error: one line, status 1.
  static func reportOutputFailure() {
    guard let failure = StandardOutput.failure else { return }
    printError("raytrace: error: cannot write to standard output: \(failure)")
    exit(withError: ExitCode.failure)
  }

  /// Parses and validates a command line as `raytrace` does, with the same
  /// outcome from the stand-in and from swift-argument-parser:
  /// - negative numbers in `--depth-range MIN MAX` and `-depth MIN MAX FILE`
  ///   are joined to their option (`NegativeValues.attached(_:)`);
  /// - an unknown option or unexpected argument is reported before what the
  ///   commands' `validate()` finds: the line is parsed once with validation
  ///   deferred, which finds everything but `validate()`'s errors, then again
  ///   with it (the real package validates a command before it looks at
  ///   what is left over, so `raytrace s.txt --outptu a.png` would say
  ///   "Nothing to render" instead of naming `--outptu`).
  static func parseCommand(_ arguments: [String]) throws -> ParsableCommand {
    let arguments = NegativeValues.attached(arguments)
    try $defersValidation.withValue(true) {
      _ = try parseAsRoot(arguments)
    }
    return try parseAsRoot(arguments)
  }
}

/// Negative numbers as the values of the options that take several numbers.
///
/// Both argument parsers read a token that starts with a dash as an option,
/// so `--depth-range -1 20` would be missing its value: `.upToNextOption`
/// stops at `-1`, and the real package has no strategy for several values
/// that may start with a dash (`.unconditional` takes one). An attached
/// value is always a value, so `--depth-range -1 20` is read as
/// `--depth-range=-1 20` and `-depth 1 -2 d.png` as `-depth 1 -depth=-2 d.png`
/// (each use adds to the option's values).
enum NegativeValues {
  /// Each option's leading values that are numbers.
  static let numberCounts = ["--depth-range": 2, "-depth": 2]

  static func attached(_ arguments: [String]) -> [String] {
    var result: [String] = []
    var index = 0
    while index < arguments.count {
      let token = arguments[index]
      index += 1
      if token == "--" {
        result += arguments[(index - 1)...]
        break
      }
      guard let count = numberCounts[token] else {
        result.append(token)
        continue
      }
      // The option's name is written before a plain value that needs it.
      var named = false
      for _ in 0..<count where index < arguments.count {
        let value = arguments[index]
        if isNegativeNumber(value) {
          result.append("\(token)=\(value)")
          named = true
        } else if value.hasPrefix("-") {
          break
        } else {
          if !named { result.append(token) }
          result.append(value)
          named = true
        }
        index += 1
      }
      if !named { result.append(token) }
    }
    return result
  }

  /// `-1`, `-0.5`, `-.5`, `-2e3`.
  static func isNegativeNumber(_ token: String) -> Bool {
    guard token.hasPrefix("-"), let second = token.dropFirst().first,
      second.isNumber || second == "."
    else {
      return false
    }
    return Double(token) != nil
  }
}

extension ImageStyle: ExpressibleByArgument {}
extension Precision: ExpressibleByArgument {}
extension IntersectionMethod: ExpressibleByArgument {}
extension PixelFilter: ExpressibleByArgument {}
extension Engine: ExpressibleByArgument {}
extension ReferencePrecision: ExpressibleByArgument {}
