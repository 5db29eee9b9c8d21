import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

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

  /// The course engine has rows of its own, in double, where it can draw
  /// the scene; a scene beyond its range (a sphere of radius 1e-300) has
  /// none. A debug build's report says its times are not representative.
  func testReport_HasTheCourseEnginesRowsAndWarnsInADebugBuild() throws {
    let outcome = try run([
      "report", "scenes/spheres.txt", "scenes/stiff/unit-sphere-1e-300.txt",
      "--size", "8", "8", "--runs", "1", "--rounds", "1",
      "--skip-antialiasing", "--plot", folder + "/plot.svg",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    XCTAssertTrue(
      outcome.stdout.contains("| spheres | double | course engine |"),
      outcome.stdout)
    XCTAssertFalse(
      outcome.stdout.contains("| unit-sphere-1e-300 | double | course"),
      outcome.stdout)
    XCTAssertTrue(
      outcome.stdout.contains("| unit-sphere-1e-300 | double | stable |"),
      outcome.stdout)
    let svg = try String(contentsOfFile: folder + "/plot.svg", encoding: .utf8)
    XCTAssertTrue(svg.hasSuffix("</svg>\n"))
    XCTAssertTrue(svg.contains("data-method=\"course\""))
    #if DEBUG
      XCTAssertTrue(
        outcome.stderr.contains("not representative")
          && outcome.stderr.contains("swift build -c release"),
        outcome.stderr)
    #else
      XCTAssertFalse(outcome.stderr.contains("debug"), outcome.stderr)
    #endif
  }

  /// A default render that takes more than 2 s says, in one line while
  /// it renders and one at the end, that the fast engine exists; a fast
  /// one, or one that names its engine, does not.
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
    // And says so while it renders, as soon as the rows done put it past
    // 2 s, not only at the end.
    XCTAssertTrue(
      slow.stderr.contains("of the rows in") && slow.stderr.contains(
        "tests every object for every ray"), slow.stderr)
    let quick = try run([
      "scenes/spheres.txt", "--size", "40", "40", "--depth", folder + "/e.png",
    ])
    XCTAssertFalse(quick.stderr.contains("--engine fast"), quick.stderr)
  }
}
