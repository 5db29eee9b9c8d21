import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import Numerics
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

  // MARK: - Scene and output errors

  func testSceneError_OneLineWithPositionAndExit1() throws {
    let scene = folder + "/bad.txt"
    try "PerspectiveCamera {\n  center 0 0 1O\n}\n".write(
      toFile: scene, atomically: true, encoding: .utf8)
    let outcome = try run([scene, "-o", folder + "/out.png"])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr, "\(scene):2:14: error: expected a number, found '1O'\n")
    XCTAssertFalse(files().contains("out.png"))
  }

  /// A value the chosen precision cannot hold is an error, not an empty
  /// image: Double holds it, Float does not.
  func testSceneError_ValueBeyondFloatExit1() throws {
    let scene = folder + "/big.txt"
    try
      (Fixtures.camera
      + "Group { numObjects 1 Sphere { center 0 0 0 radius 1e150 } }\n")
      .write(toFile: scene, atomically: true, encoding: .utf8)
    let outcome = try run([
      scene, "--precision", "float", "-o", folder + "/out.png",
    ])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr,
      "\(scene):2:51: error: '1e150' is beyond the finite range of float "
        + "(±3.4028235e+38); use --precision double\n")
    XCTAssertFalse(files().contains("out.png"))
    let double = try run([
      scene, "--size", "16", "12", "--precision", "double", "-o",
      folder + "/out.png",
    ])
    XCTAssertEqual(double.status, 0, double.stderr)
  }

  /// A sphere too small beside the rest of the scene for the precision,
  /// at any scale, is refused rather than drawn as nothing.
  func testSceneError_SphereTooSmallForFloatExit1() throws {
    let scene = folder + "/small.txt"
    try
      (Fixtures.camera
      + "Group { numObjects 1 Sphere { center 0 0 0 radius 1e-25 } }\n")
      .write(toFile: scene, atomically: true, encoding: .utf8)
    let outcome = try run([
      scene, "--precision", "float", "-o", folder + "/out.png",
    ])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr,
      "\(scene): error: a sphere of radius 1e-25 (centre 0.0 0.0 0.0) is too "
        + "small beside its distance from the eye (10.0) for float: with "
        + "that length scaled to about 1, its radius squared is below "
        + "float's normal range; use --precision double\n")
    XCTAssertFalse(files().contains("out.png"))
  }

  func testSceneError_MissingFile() throws {
    let outcome = try run([folder + "/none.txt", "-o", folder + "/out.png"])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr,
      "\(folder)/none.txt: error: cannot open the file: No such file or directory\n"
    )
  }

  func testOutputError_UnwritablePathBeforeRendering() throws {
    let outcome = try run([
      "scenes/spheres.txt", "-o", folder + "/missing/out.png",
    ])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertTrue(
      outcome.stderr.hasPrefix("raytrace: error: cannot write"), outcome.stderr)
    XCTAssertEqual(outcome.stderr.filter { $0 == "\n" }.count, 1)
  }

  // MARK: - Renders

  func testRender_EveryFormatOfEveryOutput() throws {
    let outcome = try run([
      "scenes/spheres.txt", "--size", "40", "30", "-o", folder + "/s.png",
      "--depth", folder + "/d.pfm", "--normals", folder + "/n.npy",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    XCTAssertEqual(files(), ["d.pfm", "n.npy", "s.png"])
    let shaded = try PNGDecoder.decode(try read("s.png"))
    XCTAssertEqual(shaded.width, 40)
    XCTAssertEqual(shaded.height, 30)
    XCTAssertGreaterThan(
      Set(
        stride(from: 0, to: shaded.bytes.count, by: 3).map { shaded.bytes[$0] }
      ).count, 10)
    let depth = try read("d.pfm")
    XCTAssertEqual(depth.count, "Pf\n40 30\n-1.0\n".utf8.count + 40 * 30 * 4)
    let normals = try read("n.npy")
    XCTAssertEqual(Array(normals[1..<6]), Array("NUMPY".utf8))
    XCTAssertEqual(normals.count % 64, (40 * 30 * 3 * 8) % 64)
  }

  func testRender_PPM() throws {
    let outcome = try run([
      "scenes/single-sphere.txt", "--size", "8", "6", "--normals",
      folder + "/n.ppm",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    let bytes = try read("n.ppm")
    XCTAssertEqual(bytes.count, "P6\n8 6\n255\n".utf8.count + 8 * 6 * 3)
  }

  func testRender_ThreadCountDoesNotChangeABit() throws {
    for threads in ["1", "2", "3"] {
      let outcome = try run([
        "scenes/spheres.txt", "--size", "64", "48", "--threads", threads,
        "-o", folder + "/s\(threads).png", "--depth",
        folder + "/d\(threads).pfm",
      ])
      XCTAssertEqual(outcome.status, 0, outcome.stderr)
    }
    XCTAssertEqual(try read("s1.png"), try read("s2.png"))
    XCTAssertEqual(try read("s1.png"), try read("s3.png"))
    XCTAssertEqual(try read("d1.pfm"), try read("d2.pfm"))
  }

  func testRender_AssignmentCommandLine() throws {
    let outcome = try run([
      "-input", "scenes/spheres.txt", "-size", "20", "20", "-output",
      folder + "/a.png",
      "-normals", folder + "/an.png", "-depth", "8", "18", folder + "/ad.png",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    XCTAssertEqual(files(), ["a.png", "ad.png", "an.png"])
    // The mit style paints misses in the normals image grey, (0 + 1)/2.
    let normals = try PNGDecoder.decode(try read("an.png"))
    XCTAssertEqual(normals[0, 0].0, 128)
  }

  func testStats_ReportsThroughputAndWhatWasLeftOut() throws {
    let outcome = try run([
      "scenes/spheres-only.txt", "--size", "16", "16", "--depth",
      folder + "/d.png", "--stats",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    let render = outcome.stderr.split(separator: "\n").first {
      $0.hasPrefix("render:")
    }
    XCTAssertNotNil(render, outcome.stderr)
    XCTAssertTrue(render?.contains("Mrays/s") ?? false)
    XCTAssertTrue(
      outcome.stderr.contains(
        "left out: shading (lights, materials), normals, plane tests (no planes)"
      ), outcome.stderr)
  }

  /// `--repeat` renders again in the same process for a warm median: the
  /// stats say so, and the files are those of a single render.
  func testStats_RepeatedRendersReportTheirMedianAndWriteTheSameFiles() throws {
    let once = try run([
      "scenes/spheres.txt", "--size", "40", "30", "-o", folder + "/once.png",
      "--depth", folder + "/once.npy",
    ])
    XCTAssertEqual(once.status, 0, once.stderr)
    let repeated = try run([
      "scenes/spheres.txt", "--size", "40", "30", "-o", folder + "/again.png",
      "--depth", folder + "/again.npy", "--stats", "--repeat", "3",
    ])
    XCTAssertEqual(repeated.status, 0, repeated.stderr)
    let render = repeated.stderr.split(separator: "\n").first {
      $0.hasPrefix("render:")
    }
    XCTAssertTrue(
      render?.contains("Mrays/s (median of 3 repeated renders; first render ")
        ?? false,
      repeated.stderr)
    XCTAssertEqual(try read("once.png"), try read("again.png"))
    XCTAssertEqual(try read("once.npy"), try read("again.npy"))
    let negative = try run([
      "scenes/spheres.txt", "--depth", folder + "/d.png", "--repeat", "-1",
    ])
    XCTAssertEqual(negative.status, 64)
    XCTAssertTrue(
      negative.stderr.contains("--repeat must be between 0 and 1000; got -1."))
  }

  func testReport_OneSceneMarkdownAndCSV() throws {
    let outcome = try run([
      "report", "scenes/single-sphere.txt", "--size", "16", "16", "--runs", "1",
      "--skip-antialiasing",
      "--csv", folder + "/r.csv", "--heatmaps", folder,
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    let lines = outcome.stdout.split(separator: "\n")
    // Naive and stable in each precision, and the course engine in double.
    XCTAssertEqual(lines.count, 2 + 5, outcome.stdout)
    XCTAssertTrue(
      lines[2].hasPrefix("| single-sphere | float | naive |"), String(lines[2]))
    XCTAssertTrue(
      lines[6].hasPrefix("| single-sphere | double | course engine |"),
      String(lines[6]))
    let csv = String(decoding: try read("r.csv"), as: UTF8.self)
    XCTAssertEqual(csv.split(separator: "\n").count, 6)
    XCTAssertTrue(csv.contains("\nsingle-sphere,double,course,"), csv)
    XCTAssertEqual(files().filter { $0.hasSuffix(".png") }.count, 5)
  }

  /// --reference double-double runs everywhere (on x86 it replaces the
  /// default Float80); an unknown precision is a usage error.
  func testReport_DoubleDoubleReference() throws {
    let outcome = try run([
      "report", "scenes/single-sphere.txt", "--size", "8", "8", "--runs", "1",
      "--skip-antialiasing", "--reference", "double-double",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    let lines = outcome.stdout.split(separator: "\n")
    XCTAssertEqual(lines.count, 2 + 5, outcome.stdout)
    XCTAssertTrue(
      lines[5].hasPrefix("| single-sphere | double | stable |"),
      String(lines[5]))
    let unknown = try run([
      "report", "scenes/single-sphere.txt", "--reference", "quad",
    ])
    XCTAssertEqual(unknown.status, 64, unknown.stderr)
  }

  /// A scene Float cannot hold has Double rows only.
  func testReport_DoubleOnlySceneHasNoFloatRows() throws {
    let outcome = try run([
      "report", "scenes/stiff/unit-sphere-1e200.txt", "--size", "16", "16",
      "--runs", "1", "--skip-antialiasing",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    let rows = outcome.stdout.split(separator: "\n").dropFirst(2)
    XCTAssertEqual(
      rows.map {
        $0.split(separator: "|")[1].trimmingCharacters(in: .whitespaces)
      },
      ["double", "double"], outcome.stdout)
  }

  func testReport_AntialiasingRows() throws {
    let outcome = try run([
      "report", "scenes/single-sphere.txt", "--size", "8", "8", "--runs", "1",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    let rows = outcome.stdout.split(separator: "\n").filter {
      $0.hasPrefix("| single-sphere | 4×4 |")
    }
    XCTAssertEqual(
      rows.map {
        $0.split(separator: "|")[2].trimmingCharacters(in: .whitespaces)
      }, ["1", "4", "16", "64"])
  }

  func testRender_MeshAndTransformsScene() throws {
    let outcome = try run([
      "scenes/mesh-and-transforms.txt", "--size", "40", "30", "-o",
      folder + "/m.png", "--stats",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    XCTAssertTrue(
      outcome.stderr.contains("21 triangles, 1 transformed spheres"),
      outcome.stderr)
  }

  func testRender_SupersamplingIsTheSameForAnyThreadCount() throws {
    for threads in ["1", "2"] {
      let outcome = try run([
        "scenes/spheres.txt", "--size", "32", "24", "--samples", "9",
        "--filter", "tent",
        "--threads", threads, "-o", folder + "/aa\(threads).pfm",
      ])
      XCTAssertEqual(outcome.status, 0, outcome.stderr)
    }
    XCTAssertEqual(try read("aa1.pfm"), try read("aa2.pfm"))
  }

  /// `--sample-all-outputs`: depth and normals from the samples (others
  /// than the centre's), every ray counted once; at one sample a pixel
  /// the same files as without it.
  func testRender_SampleAllOutputs() throws {
    func render(_ name: String, _ extra: [String]) throws -> Outcome {
      let outcome = try run(
        [
          "scenes/spheres.txt", "--size", "32", "24", "--depth",
          folder + "/\(name).pfm", "--normals", folder + "/\(name)n.pfm",
          "--stats",
        ] + extra)
      XCTAssertEqual(outcome.status, 0, outcome.stderr)
      return outcome
    }
    let all = try render("all", ["--samples", "4", "--sample-all-outputs"])
    XCTAssertTrue(all.stderr.contains("3072 rays"), all.stderr)
    _ = try render("centre", ["--samples", "4"])
    XCTAssertNotEqual(try read("all.pfm"), try read("centre.pfm"))
    XCTAssertNotEqual(try read("alln.pfm"), try read("centren.pfm"))
    _ = try render("one", ["--sample-all-outputs"])
    XCTAssertEqual(try read("one.pfm"), try read("centre.pfm"))
    XCTAssertEqual(try read("onen.pfm"), try read("centren.pfm"))
  }

  func testUsage_SamplesMustBeASquare() throws {
    let outcome = try run([
      "scenes/spheres.txt", "-o", folder + "/a.png", "--samples", "5",
    ])
    XCTAssertEqual(outcome.status, 64)
    XCTAssertTrue(
      outcome.stderr.contains("--samples must be a square"), outcome.stderr)
  }

  func testSceneError_DevicesAreRefusedNotRead() throws {
    // /dev/zero never ends: read, it would exhaust memory.
    var outcome = try run(["/dev/zero", "-o", folder + "/a.png"])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(outcome.stderr, "/dev/zero: error: not a regular file\n")
    let scene = folder + "/mesh.txt"
    try
      "PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }\nGroup { numObjects 1 TriangleMesh { obj_file /dev/zero } }\n"
      .write(toFile: scene, atomically: true, encoding: .utf8)
    outcome = try run([scene, "-o", folder + "/a.png"])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr,
      "\(scene):2:46: error: cannot read '/dev/zero': not a regular file\n")
  }

  // MARK: - The course's property lists and textures

  /// A plist scene is recognised by its content, whatever its name, and
  /// renders the bytes of the same scene in text.
  func testRender_PlistByContent() throws {
    let copy = folder + "/scene.txt"
    try FileManager.default.copyItem(
      atPath: Self.packageRoot + "/scenes/spheres.plist", toPath: copy)
    try run([
      "scenes/spheres.txt", "--size", "32", "24", "-o", folder + "/t.png",
    ])
    let outcome = try run([copy, "--size", "32", "24", "-o", folder + "/p.png"])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    XCTAssertEqual(try read("t.png"), try read("p.png"))
  }

  /// `--engine course` draws the default engine's image, says so in the
  /// stats, and refuses Float (it computes in the scene's Double).
  func testEngine_CourseDrawsTheSameImage() throws {
    let scene = "scenes/mesh-and-transforms.txt"
    try run([scene, "--size", "32", "24", "-o", folder + "/fast.png"])
    let course = try run([
      scene, "--size", "32", "24", "-o", folder + "/course.png", "--engine",
      "course", "--stats",
    ])
    XCTAssertEqual(course.status, 0, course.stderr)
    XCTAssertTrue(course.stderr.contains("engine course"), course.stderr)
    XCTAssertEqual(try read("fast.png"), try read("course.png"))
    let float = try run([
      scene, "-o", folder + "/f.png", "--engine", "course", "--precision",
      "float",
    ])
    XCTAssertEqual(float.status, 64, float.stderr)
    XCTAssertTrue(float.stderr.contains("--engine course"), float.stderr)
  }

  /// Textures are read only for a shaded image, and the stats say so; an
  /// unreadable texture is one line naming it, exit 1, nothing written.
  func testTextures_ReadOnlyWhenShaded() throws {
    let scene = "scenes/textured.txt"
    let depth = try run([
      scene, "--size", "16", "12", "--depth", folder + "/d.png", "--stats",
    ])
    XCTAssertEqual(depth.status, 0, depth.stderr)
    XCTAssertTrue(
      depth.stderr.contains(
        "textures: none read (no shaded image is requested)"),
      depth.stderr)
    let shaded = try run([
      scene, "--size", "16", "12", "-o", folder + "/s.png", "--stats",
    ])
    XCTAssertTrue(
      shaded.stderr.contains("textures: 2 read for the shaded image"),
      shaded.stderr)

    let text = try String(
      contentsOfFile: Self.packageRoot + "/" + scene, encoding: .utf8)
    try FileManager.default.createDirectory(
      atPath: folder + "/Meshes", withIntermediateDirectories: true)
    for mesh in ["crate", "floor"] {
      try FileManager.default.copyItem(
        atPath: Self.packageRoot + "/scenes/Meshes/\(mesh).obj",
        toPath: folder + "/Meshes/\(mesh).obj")
    }
    try text.write(
      toFile: folder + "/t.txt", atomically: true, encoding: .utf8)
    let missing = try run([folder + "/t.txt", "-o", folder + "/m.png"])
    XCTAssertEqual(missing.status, 1)
    XCTAssertEqual(
      missing.stderr,
      "\(folder)/Textures/crate.bmp: error: cannot read the texture: cannot "
        + "open the file: No such file or directory\n")
    XCTAssertFalse(files().contains("m.png"))
    let depthOnly = try run([
      folder + "/t.txt", "--size", "16", "12", "--depth", folder + "/d2.png",
    ])
    XCTAssertEqual(depthOnly.status, 0, "depth never opens a texture")
  }

  /// A plist error: one line with the key path, exit 1.
  func testSceneError_PlistKeyPath() throws {
    let path = folder + "/bad.plist"
    try """
    <?xml version="1.0" encoding="UTF-8"?>
    <plist version="1.0"><dict><key>Camera</key><dict>
    <key>center</key><string>0 0</string></dict></dict></plist>
    """.write(toFile: path, atomically: true, encoding: .utf8)
    let outcome = try run([path, "-o", folder + "/x.png"])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr,
      "\(path): error: Camera.center: expected 3 numbers, found \"0 0\"\n")
  }
}
