import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// What the command line refuses for the scale of a scene, judged from the
/// eye, and for which engine (`LengthScale.problem`, `unscaledProblem`).
extension CommandLineTests {
  /// A speck of 1e-200 three radii from an eye at x = 1: the fast engine
  /// draws it (its lengths seen from the eye are a scene at 1e-200, which
  /// it rescales); the course engine, the default, computes with the
  /// scene's own lengths, whose squares underflow, and is refused, saying
  /// so; `--check` renders with the course engine too and is refused. The
  /// same speck at 1e-25 in float is drawn.
  func testSceneError_SpeckByAFarEyeRefusedForTheCourseEngineOnly() throws {
    let scene = folder + "/speck.txt"
    try """
    PerspectiveCamera { center 1 0 0 direction 0 0 -1 up 0 1 0 angle 45 }
    Group { numObjects 1 Sphere { center 1 0 -3e-200 radius 1e-200 } }

    """.write(toFile: scene, atomically: true, encoding: .utf8)
    let message =
      "\(scene): error: the course engine, which computes with the scene's "
      + "own lengths, cannot draw a sphere of radius 1e-200 (centre 1.0 0.0 "
      + "-3e-200): its radius squared is below double's normal range; use "
      + "--engine fast\n"
    let course = try run([scene, "-o", folder + "/course.png"])
    XCTAssertEqual(course.status, 1)
    XCTAssertEqual(course.stderr, message)
    let check = try run([scene, "--check"])
    XCTAssertEqual(check.status, 1)
    XCTAssertEqual(check.stderr, message)
    let fast = try run([
      scene, "--engine", "fast", "-o", folder + "/fast.png", "--size", "32",
      "32",
    ])
    XCTAssertEqual(fast.status, 0, fast.stderr)
    XCTAssertEqual(fast.stderr, "")
    // The same in float at 1e-25: the fast engine's, and drawn.
    let floatScene = folder + "/speck-float.txt"
    try String(contentsOfFile: scene, encoding: .utf8)
      .replacingOccurrences(of: "e-200", with: "e-25")
      .write(toFile: floatScene, atomically: true, encoding: .utf8)
    let float = try run([
      floatScene, "--precision", "float", "-o", folder + "/float.png",
      "--size", "32", "32",
    ])
    XCTAssertEqual(float.status, 0, float.stderr)
  }
}
