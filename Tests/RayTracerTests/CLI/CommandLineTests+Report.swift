import Foundation
import XCTest

/// `raytrace report` reads both scene formats by content, as `render` does.
extension CommandLineTests {
  func testReport_ReadsPropertyListScenes() throws {
    let outcome = try run([
      "report", "scenes/single-sphere.plist", "--size", "8", "8", "--runs",
      "1", "--rounds", "1", "--skip-antialiasing",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    XCTAssertTrue(
      outcome.stdout.contains("| single-sphere.plist | double | stable |"),
      outcome.stdout)
  }

  /// A default render that takes more than 2 s says, in one line, that the
  /// fast engine exists; a fast one, or one that names its engine, does
  /// not.
  func testSlowDefaultRender_NamesTheFastEngine() throws {
    try skipUnlessLongTests()
    let slow = try run([
      "scenes/spheres.txt", "--size", "4000", "4000", "--threads", "1",
      "--depth", folder + "/d.png",
    ])
    XCTAssertEqual(slow.status, 0, slow.stderr)
    XCTAssertTrue(
      slow.stderr.contains("the course engine took")
        && slow.stderr.contains("--engine fast"), slow.stderr)
    let quick = try run([
      "scenes/spheres.txt", "--size", "40", "40", "--depth", folder + "/e.png",
    ])
    XCTAssertFalse(quick.stderr.contains("--engine fast"), quick.stderr)
  }
}
