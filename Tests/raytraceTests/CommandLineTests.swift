import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Runs the built `raytrace` executable, as students and graders do.
final class CommandLineTests: XCTestCase {
  struct Outcome {
    var status: Int32
    var stdout: String
    var stderr: String
  }

  static var packageRoot: String { ProjectFiles.projectFolder }

  /// Where SwiftPM put the built products, found as its package templates
  /// find it: beside the .xctest bundle on macOS (where argv[0] is
  /// `xctest`), the bundle's own folder elsewhere.
  static var productsDirectory: URL {
    #if os(macOS)
      for bundle in Bundle.allBundles
      where bundle.bundlePath.hasSuffix(".xctest") {
        return bundle.bundleURL.deletingLastPathComponent()
      }
      fatalError("cannot find the products directory")
    #else
      return Bundle.main.bundleURL
    #endif
  }

  /// The executable the test target depends on (SwiftPM builds it first).
  static var executable: String {
    productsDirectory.appendingPathComponent("raytrace").path
  }

  var folder = ""

  override func setUpWithError() throws {
    folder = NSTemporaryDirectory() + "raytrace-cli-\(UUID().uuidString)"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
  }

  override func tearDownWithError() throws {
    try? FileManager.default.removeItem(atPath: folder)
  }

  @discardableResult
  func run(_ arguments: [String]) throws -> Outcome {
    let process = Process()
    process.executableURL = URL(fileURLWithPath: Self.executable)
    process.arguments = arguments
    process.currentDirectoryURL = URL(fileURLWithPath: Self.packageRoot)
    let out = Pipe()
    let err = Pipe()
    process.standardOutput = out
    process.standardError = err
    try process.run()
    let outData = out.fileHandleForReading.readDataToEndOfFile()
    let errData = err.fileHandleForReading.readDataToEndOfFile()
    process.waitUntilExit()
    return Outcome(
      status: process.terminationStatus,
      stdout: String(decoding: outData, as: UTF8.self),
      stderr: String(decoding: errData, as: UTF8.self))
  }

  func files() -> [String] {
    ((try? FileManager.default.contentsOfDirectory(atPath: folder)) ?? [])
      .sorted()
  }

  func read(_ name: String) throws -> [UInt8] {
    Array(try Data(contentsOf: URL(fileURLWithPath: folder + "/" + name)))
  }

  // MARK: - Help and usage errors

  func testHelp_DocumentsEveryOption() throws {
    // As with swift-argument-parser, the root's help lists the subcommands
    // and `render --help` the options of the default one.
    let root = try run(["--help"])
    XCTAssertEqual(root.status, 0)
    XCTAssertTrue(root.stdout.contains("render (default)"), root.stdout)
    let outcome = try run(["render", "--help"])
    XCTAssertEqual(outcome.status, 0)
    for option in [
      "--output", "--size", "--depth", "--depth-range", "--normals", "--style",
      "--stats", "--precision", "--intersection", "--threads", "--png-level",
      "-input",
    ] {
      XCTAssertTrue(
        outcome.stdout.contains(option), "help does not mention \(option)")
    }
  }

  /// As with swift-argument-parser: after a scene, `--help` is `render`'s.
  func testHelp_SceneThenHelpIsRenderHelp() throws {
    let render = try run(["render", "--help"])
    XCTAssertTrue(
      render.stdout.contains("USAGE: raytrace render "), render.stdout)
    for arguments in [
      ["scenes/spheres.txt", "--help"], ["--help", "scenes/spheres.txt"],
      ["scenes/spheres.txt", "--outptu", "a.png", "-h"],
    ] {
      let outcome = try run(arguments)
      XCTAssertEqual(outcome.status, 0, "\(arguments)")
      XCTAssertEqual(outcome.stdout, render.stdout, "\(arguments)")
    }
  }

  /// An unknown option is named before what validation finds (here, that
  /// nothing is rendered: `a.png` is not an output), with either parser.
  func testUsage_UnknownOptionBeforeValidation() throws {
    let outcome = try run(["scenes/spheres.txt", "--outptu", "a.png"])
    XCTAssertEqual(outcome.status, 64)
    XCTAssertTrue(
      outcome.stderr.hasPrefix(
        "Error: Unknown option '--outptu'. Did you mean '--output'?\n"),
      outcome.stderr)
    let extra = try run(["scenes/spheres.txt", "extra1", "extra2"])
    XCTAssertEqual(extra.status, 64)
    XCTAssertTrue(
      extra.stderr.hasPrefix(
        "Error: 2 unexpected arguments: 'extra1', 'extra2'\n"), extra.stderr)
  }

  /// Negative depth ranges, as `--depth-range` and as the assignment's
  /// `-depth MIN MAX FILE`, with either parser; the same image either way.
  func testUsage_NegativeDepthRanges() throws {
    let cases: [(String, [String])] = [
      ("a.png", ["--depth-range", "-1", "20"]),
      ("b.png", ["--depth-range=-1", "20"]),
      ("c.png", ["-depth", "-1", "20"]),
    ]
    for (name, range) in cases {
      var arguments = [
        "-input", "scenes/spheres.txt", "-size", "16", "12",
      ]
      arguments += range
      if range[0] != "-depth" { arguments.append("--depth") }
      arguments.append(folder + "/" + name)
      let outcome = try run(arguments)
      XCTAssertEqual(outcome.status, 0, "\(arguments): \(outcome.stderr)")
    }
    XCTAssertEqual(try read("a.png"), try read("b.png"))
    XCTAssertEqual(try read("a.png"), try read("c.png"))
    let both = try run([
      "scenes/spheres.txt", "--size", "16", "12", "--depth-range", "-10", "-1",
      "--depth", folder + "/d.png",
    ])
    XCTAssertEqual(both.status, 0, both.stderr)
    let reversed = try run([
      "scenes/spheres.txt", "--depth-range", "2", "-1", "--depth",
      folder + "/e.png",
    ])
    XCTAssertEqual(reversed.status, 64)
    XCTAssertTrue(
      reversed.stderr.contains(
        "--depth-range needs finite MIN < MAX; got 2.0 -1.0."),
      reversed.stderr)
  }

  func testUsage_NoOutputIsExit64() throws {
    let outcome = try run(["scenes/spheres.txt"])
    XCTAssertEqual(outcome.status, 64)
    XCTAssertTrue(outcome.stderr.contains("Nothing to render"), outcome.stderr)
  }

  func testUsage_UnknownExtensionIsExit64() throws {
    let outcome = try run(["scenes/spheres.txt", "-o", folder + "/a.jpg"])
    XCTAssertEqual(outcome.status, 64)
    XCTAssertTrue(
      outcome.stderr.contains("Cannot tell the format"), outcome.stderr)
    XCTAssertEqual(files(), [])
  }

  func testUsage_TheSameFileTwiceIsExit64() throws {
    let path = folder + "/a.png"
    let outcome = try run(["scenes/spheres.txt", "-o", path, "--normals", path])
    XCTAssertEqual(outcome.status, 64)
  }

  func testUsage_BadSizeIsExit64() throws {
    for size in [["0", "10"], ["-5", "10"], ["1000000", "1000000"], ["10"]] {
      let outcome = try run(
        ["scenes/spheres.txt", "-o", folder + "/a.png", "--size"] + size)
      XCTAssertEqual(outcome.status, 64, "size \(size): \(outcome.stderr)")
    }
  }
}
