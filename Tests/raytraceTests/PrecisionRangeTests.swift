import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

@testable import raytrace

/// Numbers a render's precision cannot hold are refused where they are
/// written (`NumberRange.rangeProblem`), in both scene formats and in OBJ
/// meshes, instead of drawing an empty or a full image.
final class PrecisionRangeTests: XCTestCase {
  static let camera = Fixtures.camera

  /// A scene whose second line is `Group { numObjects 1 <object> }`.
  static func scene(_ object: String) -> String {
    camera + "Group { numObjects 1 \(object) }\n"
  }

  func assertError(
    _ text: String, _ precision: NumberRange, line: Int, column: Int,
    _ message: String, file: StaticString = #filePath,
    line testLine: UInt = #line
  ) {
    do throws(SceneError) {
      _ = try SceneParser.parse(
        text, file: "test.txt",
        options: SceneOptions(style: .course, precision: precision))
      XCTFail("parsed without error", file: file, line: testLine)
    } catch {
      // As the command line reports it: the remedy in its own options.
      XCTAssertEqual(
        error.report, "test.txt:\(line):\(column): error: \(message)",
        file: file, line: testLine)
    }
  }

  func parses(_ text: String, _ precision: NumberRange) -> Bool {
    (try? SceneParser.parse(
      text, file: "test.txt",
      options: SceneOptions(style: .course, precision: precision))) != nil
  }

  // MARK: - Text scenes

  func testRangeProblem_FloatOverflow() {
    // "Group { numObjects 1 Sphere { center 0 0 0 radius " is 50 bytes.
    assertError(
      Self.scene("Sphere { center 0 0 0 radius 1e150 }"), .float, line: 2,
      column: 51,
      "'1e150' is beyond the finite range of float (±3.4028235e+38); "
        + "use --precision double")
    XCTAssertTrue(
      parses(Self.scene("Sphere { center 0 0 0 radius 1e150 }"), .double))
  }

  func testRangeProblem_FloatRoundsToZeroAndToSubnormal() {
    assertError(
      Self.scene("Sphere { center 0 0 0 radius 1e-50 }"), .float, line: 2,
      column: 51,
      "'1e-50' rounds to zero in float (its smallest normal number is "
        + "1.1754944e-38); use --precision double")
    // "Group { numObjects 1 Sphere { center " is 37 bytes.
    assertError(
      Self.scene("Sphere { center 1e-40 0 0 radius 1 }"), .float, line: 2,
      column: 38,
      "'1e-40' rounds to a subnormal number in float (its smallest normal "
        + "number is 1.1754944e-38); use --precision double")
    // The smallest normal Float itself, and written zeros, are held.
    XCTAssertTrue(
      parses(
        Self.scene("Sphere { center 1.1754944e-38 -0 0.0e-99 radius 1e-25 }"),
        .float))
  }

  func testRangeProblem_Double() {
    assertError(
      Self.scene("Sphere { center 0 0 0 radius 1e-310 }"), .double, line: 2,
      column: 51,
      "'1e-310' rounds to a subnormal number in double (its smallest "
        + "normal number is 2.2250738585072014e-308)")
    assertError(
      Self.scene("Sphere { center 0 0 0 radius 1e-400 }"), .double, line: 2,
      column: 51,
      "'1e-400' rounds to zero in double (its smallest normal number is "
        + "2.2250738585072014e-308)")
    // "Group { numObjects 1 Sphere { center 0 " is 39 bytes.
    assertError(
      Self.scene("Sphere { center 0 1e400 0 radius 1 }"), .double, line: 2,
      column: 40,
      "'1e400' is beyond the finite range of double "
        + "(±1.7976931348623157e+308)")
    // Words that are not decimal numbers keep their message.
    assertError(
      Self.scene("Sphere { center 0 inf 0 radius 1 }"), .double, line: 2,
      column: 40, "expected a finite number, found 'inf'")
  }

  /// Every number is read in the precision, not only geometry.
  func testRangeProblem_CameraField() {
    assertError(
      "PerspectiveCamera { center 0 0 1e39 direction 0 0 -1 up 0 1 0 "
        + "angle 30 }\n" + Fixtures.group, .float, line: 1,
      column: 32,
      "'1e39' is beyond the finite range of float (±3.4028235e+38); "
        + "use --precision double")
  }

  /// Each factor holds in Float; their product does not, and no
  /// rescaling of the scene saves a dimensionless matrix entry.
  func testRangeProblem_TransformProductOverflows() {
    let text = Self.scene(
      "Transform { UniformScale 1e20 UniformScale 1e20 "
        + "Sphere { center 0 0 0 radius 1 } }")
    assertError(
      text, .float, line: 2, column: 22,
      "the Transform's matrix overflows: its entry 1e+40 is beyond the "
        + "finite range of float; use --precision double")
    XCTAssertTrue(parses(text, .double))
    // The inverse: 1e-20 · 1e-20 is subnormal in Float, its inverse 1e40.
    assertError(
      Self.scene(
        "Transform { UniformScale 1e-20 UniformScale 1e-20 "
          + "Sphere { center 0 0 0 radius 1 } }"), .float, line: 2,
      column: 22,
      "the Transform's inverse overflows: its entry 1e+40 is beyond the "
        + "finite range of float; use --precision double")
  }

  func testRangeProblem_TransformMovesBeyondFloat() {
    assertError(
      Self.scene(
        "Transform { UniformScale 1e20 Sphere { center 0 0 0 radius 1e20 } }"),
      .float, line: 2, column: 22,
      "the Transform takes its object beyond float's range: a coordinate, "
        + "offset or normal is no longer finite, or a radius becomes 0 or "
        + "subnormal; use --precision double")
  }

  /// Plain spheres read in one pass are checked as the slow path checks
  /// them, at the same position.
  func testRangeProblem_ManyPlainSpheres() {
    var text = Self.camera + "Group {\n  numObjects 100\n"
    for index in 0..<99 {
      text += "  Sphere { center \(index) 0 0  radius 0.5 }\n"
    }
    text += "  Sphere { center 0 0 0  radius 3e38 }\n}\n"
    XCTAssertTrue(parses(text, .float))
    assertError(
      text.replacingOccurrences(of: "3e38", with: "4e38"), .float,
      line: 103, column: 33,
      "'4e38' is beyond the finite range of float (±3.4028235e+38); "
        + "use --precision double")
  }

  // MARK: - OBJ meshes

  func testRangeProblem_OBJVertex() {
    XCTAssertThrowsError(
      try OBJReader.parse(
        "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n", file: "m.obj",
        precision: .float)
    ) { error in
      XCTAssertEqual(
        (error as? SceneError)?.report,
        "m.obj:3:5: error: the y coordinate of 'v': '1e39' is beyond the "
          + "finite range of float (±3.4028235e+38); use --precision double")
    }
    XCTAssertNoThrow(
      try OBJReader.parse(
        "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n", file: "m.obj"))
  }

  // MARK: - Property lists

  func testRangeProblem_PlistKeyPath() throws {
    let body =
      Fixtures.plistCamera
      + "<key>Group</key><array><dict><key>type</key><string>Sphere</string>"
      + "<key>center</key><string>0 0 0</string>"
      + "<key>radius</key><string>1e-45</string></dict></array>"
    let bytes = Array(
      ("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<plist version=\"1.0\">"
        + "<dict>\(body)</dict></plist>").utf8)
    XCTAssertThrowsError(
      try SceneReader.parse(
        bytes: bytes, file: "C08_C.plist",
        options: SceneOptions(style: .course, precision: .float))
    ) { error in
      XCTAssertEqual(
        (error as? SceneError)?.report,
        "C08_C.plist: error: Group[0].radius: '1e-45' rounds to a subnormal "
          + "number in float (its smallest normal number is 1.1754944e-38); "
          + "use --precision double")
    }
    XCTAssertNoThrow(try SceneReader.parse(bytes: bytes, file: "C08_C.plist"))
  }
}
