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
}
