import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Outputs that are not plain files, names the final rename would refuse,
/// and the other commands' outputs: all checked before any work.
extension OutputSafetyTests {
  /// A FIFO with a reader waiting gets the image, and stays a FIFO; one
  /// without a reader is refused at once rather than blocking.
  func testOutputIntoAFIFO() throws {
    let fifo = folder + "/pipe.png"
    XCTAssertEqual(mkfifo(fifo, 0o644), 0)
    let refused = try run([
      "scenes/spheres.txt", "--size", "20", "20", "-o", fifo,
    ])
    XCTAssertEqual(refused.status, 1)
    XCTAssertTrue(
      refused.stderr.contains("it is a FIFO with no reader"), refused.stderr)
    // The reader: this test, its end open before the run starts (a small
    // image fits in the pipe's buffer, read once the run has ended).
    let reader = open(fifo, O_RDONLY | O_NONBLOCK)
    XCTAssertGreaterThanOrEqual(reader, 0)
    defer { close(reader) }
    let written = try run([
      "scenes/spheres.txt", "--size", "20", "20", "-o", fifo,
    ])
    var buffer = [UInt8](repeating: 0, count: 65536)
    let count = buffer.withUnsafeMutableBytes {
      PlatformSupport.read(reader, $0.baseAddress, $0.count)
    }
    let data = buffer.prefix(max(count, 0))
    XCTAssertEqual(written.status, 0, written.stderr)
    XCTAssertEqual(Array(data.prefix(4)), [0x89, 0x50, 0x4E, 0x47], "a PNG")
    var status = stat()
    XCTAssertEqual(stat(fifo, &status), 0)
    XCTAssertEqual(status.st_mode & S_IFMT, S_IFIFO, "still a FIFO")
  }

  /// A character device (here /dev/null, through a link with an image's
  /// name) is written into, never replaced by a file.
  func testOutputIntoADevice() throws {
    let link = folder + "/null.png"
    XCTAssertEqual(symlink("/dev/null", link), 0)
    let outcome = try run([
      "scenes/spheres.txt", "--size", "20", "20", "-o", link,
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    var status = stat()
    XCTAssertEqual(stat("/dev/null", &status), 0)
    XCTAssertEqual(status.st_mode & S_IFMT, S_IFCHR, "/dev/null is a device")
    XCTAssertEqual(lstat(link, &status), 0)
    XCTAssertEqual(status.st_mode & S_IFMT, S_IFLNK, "the link is a link")
  }

  /// A name longer than the folder allows is refused before the render,
  /// not after it (the rename would have failed).
  func testNameTooLong_RefusedBeforeRendering() throws {
    let start = Date()
    let name = String(repeating: "n", count: 300) + ".png"
    let outcome = try run([
      "scenes/spheres.txt", "--size", "3000", "3000", "--samples", "16",
      "-o", folder + "/" + name,
    ])
    XCTAssertEqual(outcome.status, 1)
    XCTAssertTrue(
      outcome.stderr.contains(
        "its name is 304 bytes long, and the folder allows at most"),
      outcome.stderr)
    XCTAssertLessThan(Date().timeIntervalSince(start), 5, "before the render")
    XCTAssertEqual(files(), [])
  }

  /// `report --csv` naming the scene is refused before any work; heatmaps
  /// of two scenes with one name in different folders are both kept.
  func testReportOutputs() throws {
    for sub in ["a", "b"] {
      try FileManager.default.createDirectory(
        atPath: "\(folder)/\(sub)", withIntermediateDirectories: true)
      try FileManager.default.copyItem(
        atPath: CommandLineTests.packageRoot + "/scenes/single-sphere.txt",
        toPath: "\(folder)/\(sub)/s.txt")
    }
    let scene = folder + "/a/s.txt"
    let before = try read("a/s.txt")
    let refused = try run(["report", scene, "--csv", scene])
    XCTAssertEqual(refused.status, 64)
    XCTAssertTrue(
      refused.stderr.contains("would overwrite the scene file"), refused.stderr)
    XCTAssertEqual(try read("a/s.txt"), before)
    let both = try run([
      "report", scene, folder + "/b/s.txt", "--size", "8", "8", "--runs", "1",
      "--rounds", "1", "--skip-antialiasing", "--heatmaps", folder + "/maps",
    ])
    XCTAssertEqual(both.status, 0, both.stderr)
    let maps = try FileManager.default.contentsOfDirectory(
      atPath: folder + "/maps")
    // Two scenes: naive and stable in each precision, the course engine.
    XCTAssertEqual(maps.count, 10, "\(maps)")
    XCTAssertTrue(maps.contains("s-2-double-stable.png"), "\(maps)")
    XCTAssertTrue(maps.contains("s-2-double-course.png"), "\(maps)")
    // --plot is refused over a scene as --csv is.
    let plotOver = try run(["report", scene, "--plot", scene])
    XCTAssertEqual(plotOver.status, 64)
    XCTAssertTrue(
      plotOver.stderr.contains("--plot")
        && plotOver.stderr.contains(
          "would overwrite the scene file"),
      plotOver.stderr)
    XCTAssertEqual(try read("a/s.txt"), before)
    // A device named as the CSV is written into, never replaced.
    let null = folder + "/null.csv"
    XCTAssertEqual(symlink("/dev/null", null), 0)
    let device = try run([
      "report", scene, "--size", "8", "8", "--runs", "1", "--rounds", "1",
      "--skip-antialiasing", "--csv", null,
    ])
    XCTAssertEqual(device.status, 0, device.stderr)
    var status = stat()
    XCTAssertEqual(stat("/dev/null", &status), 0)
    XCTAssertEqual(status.st_mode & S_IFMT, S_IFCHR, "/dev/null is a device")
  }

  /// A write to standard output that fails is an error, not exit 0.
  func testStandardOutputFull_IsAnError() throws {
    let outcome = try run(
      [
        "report", "scenes/single-sphere.txt", "--size", "8", "8", "--runs", "1",
        "--rounds", "1", "--skip-antialiasing",
      ],
      shell: "exec >/dev/full;")
    XCTAssertEqual(outcome.status, 1)
    XCTAssertTrue(
      outcome.stderr.contains("cannot write to standard output"), outcome.stderr
    )
  }

  /// An image whose buffers cannot fit in what the process may use (here
  /// an address-space limit of 1.5 GiB) is refused before anything is
  /// allocated or created, with what it needs and the limit: the machine's
  /// limit, one line and status 1, not a usage error (64 and the usage).
  func testMemoryLimit_RefusedBeforeAnyWork() throws {
    let outcome = try run(
      [
        "scenes/spheres.txt", "--size", "8192", "8192", "--depth",
        folder + "/d.npy", "--normals", folder + "/n.npy", "-o",
        folder + "/c.npy",
      ], shell: "ulimit -v 1572864;")
    XCTAssertEqual(outcome.status, 1)
    XCTAssertFalse(outcome.stderr.contains("USAGE"), outcome.stderr)
    XCTAssertTrue(outcome.stderr.hasPrefix("raytrace: error: "), outcome.stderr)
    XCTAssertTrue(
      outcome.stderr.contains(
        "would need about 7.38 GiB of memory for these outputs, and the "
          + "process may use at most 1.50 GiB (its address-space limit"),
      outcome.stderr)
    XCTAssertEqual(files(), [])
  }
}
