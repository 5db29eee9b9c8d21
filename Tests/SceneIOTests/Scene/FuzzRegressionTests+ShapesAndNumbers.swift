import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import FastEngine
@testable import FastKernels
@testable import PlatformSupport
import TestSupport

extension FuzzRegressionTests {
  // MARK: - Transforms

  static let beyondDouble =
    "the Transform takes its object beyond Double's range: a coordinate, "
    + "offset or normal is no longer finite, or a radius becomes 0"

  /// Found by the fuzzer's check that the parsed scene, transforms
  /// applied, holds only finite geometry: every number in the file is
  /// finite, but what a Transform makes of it need not be. Each case fails
  /// at the outermost Transform (line 2, column 22).
  func testTransform_GeometryBeyondDoubleIsAnError() {
    func transform(_ body: String) -> String {
      Self.camera + "Group { numObjects 1 Transform { \(body) } }"
    }
    // The plane's normal through the inverse transpose is NaN.
    assertError(
      transform("UniformScale 1e300 Plane { normal 0 0 1 offset 1 }"), line: 2,
      column: 22, Self.beyondDouble)
    assertError(
      transform(
        "UniformScale 1e300 Triangle { vertex0 0 0 0 vertex1 1e300 0 0 "
          + "vertex2 0 1e300 0 }"
      ),
      line: 2, column: 22, Self.beyondDouble)
    // A radius of 1e-200 scaled by 1e-150 underflows to 0.
    assertError(
      transform("UniformScale 1e-150 Sphere { center 0 0 0 radius 1e-200 }"),
      line: 2,
      column: 22, Self.beyondDouble)
    // Each matrix is finite; their product is not.
    assertError(
      transform(
        "Matrix4f 1e300 0 0 0 0 1e300 0 0 0 0 1e300 0 0 0 0 1 Transform { "
          + "Matrix4f 1e300 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 \(Self.sphere) }"),
      line: 2, column: 22, Self.beyondDouble)
  }

  /// A matrix that overflows while it is composed was reported as having
  /// no inverse.
  func testTransform_OverflowingMatrixSaysSo() {
    assertError(
      Self.camera
        + "Group { numObjects 1 Transform { Translate 1e308 0 0 Translate "
        + "1e308 0 0 "
        + "\(Self.sphere) } }",
      line: 2, column: 22,
      "the Transform's matrix overflows: its entries are not all finite")
  }

  /// Large but representable transforms still parse.
  func testTransform_LargeButFiniteParses() throws {
    let scene = try parse(
      Self.camera
        + "Group { numObjects 1 Transform { UniformScale 1e100 "
        + "Sphere { center 0 0 0 radius 1e100 } } }")
    XCTAssertEqual(scene.root.flattened().spheres.map(\.radius), [1e200])
  }

  // MARK: - Meshes

  /// The OBJ path is used as written: escaping its control characters, as
  /// messages do, named another file. The message escapes them.
  func testMesh_PathIsUsedAsWrittenAndQuotedEscaped() throws {
    let folder = NSTemporaryDirectory() + "raytrace-fuzz-\(UUID().uuidString)"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
    defer { try? FileManager.default.removeItem(atPath: folder) }
    let path = folder + "/tri\u{7}angle.obj"
    try Data("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".utf8)
      .write(to: URL(fileURLWithPath: path))
    let scene = try parse(
      Self.camera + "Group { numObjects 1 TriangleMesh { obj_file \(path) } }")
    XCTAssertEqual(scene.root.flattened().triangles.count, 1)

    assertError(
      Self.camera
        + "Group { numObjects 1 TriangleMesh { obj_file no\u{1B}such.obj } }",
      line: 2, column: 46,
      "cannot read 'no\\u{1B}such.obj': cannot open the file: No such file or "
        + "directory")
  }

  // MARK: - Files

  /// A FIFO named as a scene hung in fopen, waiting for a writer, before
  /// the check for regular files could refuse it.
  func testReadFile_FIFOIsRefusedWithoutWaiting() throws {
    let path = NSTemporaryDirectory() + "raytrace-fifo-\(UUID().uuidString)"
    XCTAssertEqual(mkfifo(path, 0o600), 0, String(cString: strerror(errno)))
    defer { unlink(path) }
    // Should the open wait after all, a writer arrives after 5 s, so that
    // the test fails on its time rather than hanging the suite.
    DispatchQueue.global().asyncAfter(deadline: .now() + 5) {
      let writer = open(path, O_WRONLY | O_NONBLOCK)
      if writer >= 0 { close(writer) }
    }
    let start = Date()
    XCTAssertThrowsError(try SceneParser.parse(contentsOf: path)) { error in
      XCTAssertEqual("\(error)", "\(path): error: not a regular file")
    }
    XCTAssertLessThan(Date().timeIntervalSince(start), 4)
  }

  // MARK: - Numbers

  /// Exponents and mantissas far beyond Double's range: both overflow and
  /// underflow to zero are refused, naming the precision (see
  /// PrecisionRangeTests); a written zero reads as zero.
  func testNumbers_ExtremeExponentsAndLengths() throws {
    func sphere(center: String = "0", radius: String = "1") -> String {
      Self.camera
        + "Group { numObjects 1 Sphere { center \(center) 0 0 radius "
        + "\(radius) } }"
    }
    assertError(
      sphere(radius: "1e999999999"), line: 2, column: 51,
      "'1e999999999' is beyond the finite range of double "
        + "(±1.7976931348623157e+308)")
    assertError(
      sphere(center: "-1e999999999"), line: 2, column: 38,
      "'-1e999999999' is beyond the finite range of double "
        + "(±1.7976931348623157e+308)")
    assertError(
      sphere(radius: "1e-999999999"), line: 2, column: 51,
      "'1e-999999999' rounds to zero in double (its smallest normal number "
        + "is 2.2250738585072014e-308)")
    let exponent = "1e" + String(repeating: "9", count: 4000)
    assertError(
      sphere(radius: exponent), line: 2, column: 51,
      "'\(exponent)' is beyond the finite range of double "
        + "(±1.7976931348623157e+308)")
    let mantissa = "1" + String(repeating: "0", count: 4000)
    assertError(
      sphere(radius: mantissa), line: 2, column: 51,
      "'\(mantissa)' is beyond the finite range of double "
        + "(±1.7976931348623157e+308)")

    for center in [
      "1e-999999999", "0." + String(repeating: "0", count: 4000) + "1",
    ] {
      XCTAssertThrowsError(try parse(sphere(center: center)), center)
    }
    for center in ["0e999999999", "-0." + String(repeating: "0", count: 4000)] {
      let scene = try parse(sphere(center: center))
      XCTAssertEqual(
        scene.root.flattened().spheres.map(\.center), [.zero], center)
    }
  }
}
