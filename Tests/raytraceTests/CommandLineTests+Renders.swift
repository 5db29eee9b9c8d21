import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension CommandLineTests {
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
        "left out: shading (lights, materials), normals, plane tests (no "
          + "planes)"
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
      ("PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }"
        + "\nGroup { numObjects 1 TriangleMesh { obj_file /dev/zero } }\n")
      .write(toFile: scene, atomically: true, encoding: .utf8)
    outcome = try run([scene, "-o", folder + "/a.png"])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertEqual(
      outcome.stderr,
      "\(scene):2:46: error: cannot read '/dev/zero': not a regular file\n")
  }
}
