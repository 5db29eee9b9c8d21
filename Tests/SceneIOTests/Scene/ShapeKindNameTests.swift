import Geometry
import SceneDescription
import SceneIO
import TestSupport
import XCTest

/// A shape of one's own named like a kind of the scene formats would take
/// that kind's place without a word: both readers refuse the options
/// instead, naming the shape, as they refuse two shapes of one name.
final class ShapeKindNameTests: XCTestCase {
  /// Hits nothing: only its name is read here.
  struct Nothing: Hittable {
    func intersect(
      _ ray: Ray<Double>, after tMin: Double, before tMax: Double
    ) -> Hit<Double>? { nil }

    var boundingBox: BoundingBox? { nil }
  }

  static func kind(_ name: String) -> ShapeKind {
    ShapeKind(name: name, fields: []) { _, _ in .success(Nothing()) }
  }

  static let text = Fixtures.camera + Fixtures.group
  static let plist = """
    <?xml version="1.0" encoding="UTF-8"?>
    <plist version="1.0"><dict>\(Fixtures.plistCamera)
    <key>Group</key><array></array></dict></plist>
    """

  /// The message each reader gives for `shapes`, or nil when it reads.
  func messages(_ shapes: [ShapeKind]) -> [String?] {
    let options = SceneOptions(style: .course, shapes: shapes)
    return [Self.text, Self.plist].map { text -> String? in
      do throws(SceneError) {
        _ = try SceneReader.parse(
          bytes: Array(text.utf8), file: "s", options: options)
        return nil
      } catch {
        return error.description
      }
    }
  }

  func testNativeName_Refused() {
    for name in ["Sphere", "Plane", "Triangle", "TriangleMesh", "Group"] {
      XCTAssertEqual(
        messages([Self.kind(name)]),
        Array(
          repeating: "s: error: the shape of one's own '\(name)' is named "
            + "like the scene formats' own \(name): give it a name of "
            + "its own", count: 2), name)
    }
  }

  func testTwoShapesOfOneName_Refused() {
    XCTAssertEqual(
      messages([Self.kind("Disc"), Self.kind("Disc")]),
      Array(
        repeating: "s: error: two shapes of one's own are named 'Disc': "
          + "give each a name of its own", count: 2))
  }

  func testNamesOfTheirOwn_Read() {
    XCTAssertEqual(
      messages([Self.kind("Disc"), Self.kind("Torus")]), [nil, nil])
  }
}
