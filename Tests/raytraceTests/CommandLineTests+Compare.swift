import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `raytrace compare` and `raytrace SCENE --check`, run as a student runs
/// them: their lines and exit statuses.
extension CommandLineTests {
  func writePPM(_ name: String, _ bytes: [UInt8], width: Int, height: Int)
    throws
  {
    let image = Image8(width: width, height: height, bytes: bytes)
    try Data(PPMEncoder.encode(image)).write(
      to: URL(fileURLWithPath: folder + "/" + name))
  }

  func testCompare_StatusesAndLines() throws {
    let a = (0..<48).map { UInt8($0 * 5) }
    try writePPM("a.ppm", a, width: 4, height: 4)
    try writePPM("b.ppm", a.map { $0 &+ 1 }, width: 4, height: 4)
    try writePPM("c.ppm", a.reversed(), width: 4, height: 4)
    try writePPM("small.ppm", Array(a.prefix(12)), width: 2, height: 2)
    let same = try run(["compare", folder + "/a.ppm", folder + "/b.ppm"])
    XCTAssertEqual(same.status, 0, same.stderr)
    XCTAssertTrue(same.stdout.contains("within 2 levels: 100 %"), same.stdout)
    let different = try run([
      "compare", folder + "/a.ppm", folder + "/c.ppm", "--diff",
      folder + "/d.png",
    ])
    XCTAssertEqual(different.status, 1)
    XCTAssertTrue(different.stdout.contains("FAIL"), different.stdout)
    XCTAssertEqual(
      try ImageFileReader.read(read("d.png")).width, 4, "the difference map")
    let sizes = try run(["compare", folder + "/a.ppm", folder + "/small.ppm"])
    XCTAssertEqual(sizes.status, 1)
    XCTAssertTrue(sizes.stderr.contains("is 4×4 and"), sizes.stderr)
    XCTAssertEqual(sizes.stderr.split(separator: "\n").count, 1)
    let missing = try run(["compare", folder + "/a.ppm", folder + "/none.png"])
    XCTAssertEqual(missing.status, 2)
    XCTAssertTrue(
      missing.stderr.hasPrefix("raytrace: error: cannot read '"),
      missing.stderr)
    let usage = try run([
      "compare", folder + "/a.ppm", folder + "/b.ppm", "--need", "120",
    ])
    XCTAssertEqual(usage.status, 64)
    let over = try run([
      "compare", folder + "/a.ppm", folder + "/b.ppm", "--diff",
      folder + "/./a.ppm",
    ])
    XCTAssertEqual(over.status, 64, "--diff over an image, however spelt")
    XCTAssertEqual(try read("a.ppm").count, 48 + 11)
  }

  func testCheck_TheEnginesAgreeOnAProjectScene() throws {
    let outcome = try run([
      "scenes/spheres.txt", "--check", "--size", "64", "48",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stdout + outcome.stderr)
    for name in ["shaded:", "normals:", "depth:"] {
      XCTAssertTrue(outcome.stdout.contains(name), outcome.stdout)
    }
    XCTAssertTrue(outcome.stdout.contains("pattern: identical"), outcome.stdout)
    XCTAssertEqual(files(), [], "no output asked for, none written")
    let written = try run([
      "scenes/spheres.txt", "--check", "--size", "64", "48", "-o",
      folder + "/o.png",
    ])
    XCTAssertEqual(written.status, 0, written.stderr)
    XCTAssertEqual(files(), ["o.png"])
    let refused = try run([
      "scenes/spheres.txt", "--check", "--engine", "fast",
    ])
    XCTAssertEqual(refused.status, 64)
  }
}
