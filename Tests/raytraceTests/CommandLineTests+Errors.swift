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
      "\(folder)/none.txt: error: cannot open the file: No such file or "
        + "directory\n"
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
}
