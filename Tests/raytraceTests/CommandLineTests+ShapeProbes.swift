import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `raytrace SCENE --check` asks the course's shapes with its own rays
/// before it renders (`ShapeProbes`); on the course's code they pass, and
/// the images are compared as before.
extension CommandLineTests {
  func testCheck_ProbesTheScenesShapesFirst() throws {
    let outcome = try run([
      "scenes/mesh-and-transforms.txt", "--check", "--size", "64", "48",
    ])
    XCTAssertEqual(outcome.status, 0, outcome.stdout + outcome.stderr)
    let lines = outcome.stdout.split(
      separator: "\n", omittingEmptySubsequences: false)
    XCTAssertEqual(
      lines.first,
      "shape probes (rays whose answers are known, before rendering): "
        + "Sphere passed 9, Plane passed 7, Triangle passed 10, Transform "
        + "passed 4")
    XCTAssertTrue(
      outcome.stdout.contains("course engine against fast engine"),
      outcome.stdout)
    XCTAssertTrue(outcome.stdout.contains("pattern: identical"), outcome.stdout)
    XCTAssertFalse(outcome.stdout.contains("not compared"), outcome.stdout)
  }
}
