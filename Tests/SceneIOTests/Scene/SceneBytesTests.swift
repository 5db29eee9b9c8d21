import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

final class SceneBytesTests: XCTestCase {
  var path = ""

  override func setUp() {
    path =
      FileManager.default.temporaryDirectory
      .appendingPathComponent("raytrace-scene-bytes-\(UUID().uuidString)").path
  }

  override func tearDown() {
    try? FileManager.default.removeItem(atPath: path)
  }

  /// Every byte, whether the file is read whole or in halves: sizes
  /// around the threshold, and odd sizes whose halves are not pages.
  func testContentsOf_EveryByteWholeOrInHalves() throws {
    var generator = SplitMix64(seed: 0x5CE4E)
    let threshold = SceneBytes.splitThreshold
    for count in [0, 1, 4096, threshold - 1, threshold, threshold + 4097] {
      let bytes = (0..<count).map { _ in
        UInt8(truncatingIfNeeded: generator.next())
      }
      try Data(bytes).write(to: URL(fileURLWithPath: path))
      let read = try SceneBytes.contentsOf(path)
      XCTAssertEqual(Array(read.buffer), bytes, "\(count) bytes")
    }
  }

  /// Every byte, read by 1, 2, 3, 7 or 16 threads: one part per thread,
  /// each of at least half the threshold (16 parts of 8 MiB and a bit,
  /// whose parts are not pages).
  func testContentsOf_EveryByteAnyThreads() throws {
    var generator = SplitMix64(seed: 0x5CE50)
    let count = 16 * SceneBytes.splitThreshold / 2 + 4097
    // Eight bytes a draw: a byte a draw took a second of the unoptimised
    // debug build.
    let words = (0..<(count + 7) / 8).map { _ in generator.next() }
    let bytes = words.withUnsafeBytes { Array($0.prefix(count)) }
    try Data(bytes).write(to: URL(fileURLWithPath: path))
    for threads in runsLongTests ? [1, 2, 3, 7, 16] : [1, 3, 16] {
      let read = try SceneBytes.contentsOf(path, threads: threads)
      XCTAssertTrue(Array(read.buffer) == bytes, "\(threads) threads")
    }
  }

  /// A scene read in halves parses to the scene its bytes give, to the
  /// bit, and its errors carry the file's name and their position.
  func testParse_SceneReadInHalvesAsItsBytes() throws {
    var text = SceneParserTests.camera + "Group {\n  numObjects 30000\n"
    var generator = SplitMix64(seed: 0x5CE4F)
    for _ in 0..<30_000 {
      let v = (0..<4).map { _ in
        String(format: "%.7g", generator.logUniform(1e-3, 1e3) as Double)
      }
      text += "  Sphere { center \(v[0]) -\(v[1]) \(v[2])  radius \(v[3]) }\n"
    }
    let whole = text + "}\n"
    try whole.write(toFile: path, atomically: false, encoding: .utf8)
    XCTAssertGreaterThan(whole.utf8.count, SceneBytes.splitThreshold)
    let mapped = try SceneParser.parse(contentsOf: path)
    let fromBytes = try SceneParser.parse(bytes: Array(whole.utf8), file: path)
    XCTAssertEqual(mapped.root.objects.count, 30_000)
    XCTAssertEqual(
      SceneTokenizerTests.sphereBits(mapped.root),
      SceneTokenizerTests.sphereBits(fromBytes.root))

    try (text + "  Sphere { center 0 0 0 radius 1 }\n}\n").write(
      toFile: path, atomically: false, encoding: .utf8)
    XCTAssertThrowsError(try SceneParser.parse(contentsOf: path)) { error in
      XCTAssertEqual(
        "\(error)",
        "\(path):30004:3: error: Group has more objects than numObjects "
          + "(line 3) says (30000)")
    }
  }

  /// Refused before anything is read, with the system's reason.
  func testContentsOf_RefusesWhatIsNotARegularFile() {
    for (name, reason) in [
      (path + ".missing", "cannot open the file: No such file or directory"),
      (FileManager.default.temporaryDirectory.path, "not a regular file"),
      ("/dev/zero", "not a regular file"),
    ] {
      XCTAssertThrowsError(try SceneBytes.contentsOf(name)) { error in
        XCTAssertEqual((error as? FileReadError)?.reason, reason, name)
      }
    }
  }
}
