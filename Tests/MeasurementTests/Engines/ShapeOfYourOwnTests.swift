import Course
import SceneIO
import Pipeline
import Geometry
import SceneDescription
import XCTest

/// A shape of the test's own, defined in one place (docs/ADDING-A-SHAPE.md),
/// renders in both engines: the course engine asks it directly, the fast
/// engine through the same protocol behind its box.
final class ShapeOfYourOwnTests: XCTestCase {
  /// A disc: the points of a plane within `radius` of `center`.
  struct Disc: Hittable {
    var center: Vector3<Double>
    var normal: Vector3<Double>
    var radius: Double
    var materialIndex: Int

    func intersect(
      _ ray: Ray<Double>, after tMin: Double, before tMax: Double
    ) -> Hit<Double>? {
      let t = normal.dot(center - ray.origin) / normal.dot(ray.direction)
      guard tMin < t, t < tMax,
        (ray.point(at: t) - center).lengthSquared <= radius * radius
      else { return nil }
      return Hit(t: t, normal: normal, materialIndex: materialIndex)
    }

    var boundingBox: BoundingBox? {
      let reach = Vector3(radius, radius, radius)
      return BoundingBox(lower: center - reach, upper: center + reach)
    }
  }

  /// A red disc facing the camera behind a white sphere, and a second disc
  /// moved and stretched by a transform.
  func scene() throws -> Scene {
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0, 0, 10), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 40))
    let disc = Disc(
      center: .zero, normal: Vector3(0, 0, 1), radius: 2.5, materialIndex: 1)
    let moved = try XCTUnwrap(
      SceneDescription.Transform<Double>(
        matrix: .translation(Vector3(2, 2, 1)) * .scale(Vector3(1, 0.3, 1)),
        object: .shape(Shape(disc))))
    return Scene(
      camera: camera,
      materials: [
        Material(diffuse: Vector3(1, 1, 1)),
        Material(diffuse: Vector3(1, 0, 0)),
      ],
      root: SceneDescription.Group([
        .sphere(SceneDescription.Sphere(center: Vector3(1, 0, 2), radius: 1)),
        .shape(Shape(disc)), .transform(moved),
      ]))
  }

  func testDisc_RendersInBothEngines() throws {
    let both = BothEngines(
      try scene(), width: 64, height: 48, style: .course)
    // Unlit, a red material shows its diffuse colour (the ambient light is
    // white in a scene without lights).
    let discPixels = both.course.color.indices.filter {
      both.course.color[$0] == Vector3(1, 0, 0)
    }
    XCTAssertGreaterThan(discPixels.count, 200, "the disc is drawn")
    for pixel in discPixels {
      XCTAssertEqual(both.fast.depth[pixel], both.course.depth[pixel])
      XCTAssertEqual(both.fast.color[pixel], Vector3(1, 0, 0))
      XCTAssertEqual(both.fast.normals[pixel], Vector3(0, 0, 1))
    }
    for (name, course, fast) in both.images {
      XCTAssertEqual(course, fast, "\(name): the same pixels")
    }
  }

  /// The disc as the readers learn it: one `ShapeKind`.
  static let discKind = ShapeKind(
    name: "Disc", fields: [("center", 3), ("normal", 3), ("radius", 1)]
  ) { values, material in
    guard let c = values["center"], let n = values["normal"],
      let r = values["radius"]?.first
    else { return .failure(ShapeError("a field is missing")) }
    guard r > 0 else {
      return .failure(ShapeError("'radius' must be positive"))
    }
    return .success(
      Disc(
        center: Vector3(c[0], c[1], c[2]),
        normal: Vector3(n[0], n[1], n[2]).normalized(), radius: r,
        materialIndex: material))
  }

  static let text = """
    PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 40 }
    Materials {
      numMaterials 2
      PhongMaterial { diffuseColor 1 1 1 }
      PhongMaterial { diffuseColor 1 0 0 }
    }
    Group {
      numObjects 2
      MaterialIndex 0
      Sphere { center 1 0 2 radius 1 }
      MaterialIndex 1
      Disc { radius 2.5 normal 0 0 1 center 0 0 0 }
    }
    """

  static let plist = """
    <?xml version="1.0" encoding="UTF-8"?>
    <plist version="1.0"><dict>
    <key>Camera</key><dict>
      <key>type</key><string>PerspectiveCamera</string>
      <key>center</key><string>0 0 10</string>
      <key>direction</key><string>0 0 -1</string>
      <key>up</key><string>0 1 0</string>
      <key>angle</key><string>40</string></dict>
    <key>Materials</key><array>
      <dict><key>type</key><string>PhongMaterial</string>
        <key>diffuseColor</key><string>1 1 1</string></dict>
      <dict><key>type</key><string>PhongMaterial</string>
        <key>diffuseColor</key><string>1 0 0</string></dict></array>
    <key>Group</key><array>
      <dict><key>type</key><string>Sphere</string>
        <key>materialIndex</key><string>0</string>
        <key>center</key><string>1 0 2</string>
        <key>radius</key><string>1</string></dict>
      <dict><key>type</key><string>Disc</string>
        <key>materialIndex</key><string>1</string>
        <key>center</key><string>0 0 0</string>
        <key>normal</key><string>0 0 1</string>
        <key>radius</key><string>2.5</string></dict></array>
    </dict></plist>
    """

  /// Both formats read the disc by its name, and both engines draw it.
  func testDisc_ReadByBothFormats() throws {
    let options = SceneOptions(style: .course, shapes: [Self.discKind])
    for (name, source) in [("disc.txt", Self.text), ("disc.plist", Self.plist)]
    {
      let scene = try SceneReader.parse(
        bytes: Array(source.utf8), file: name, options: options)
      let both = BothEngines(scene, width: 48, height: 36, style: .course)
      let red = both.course.color.filter { $0 == Vector3(1, 0, 0) }.count
      XCTAssertGreaterThan(red, 100, "\(name): the disc is drawn")
      for (output, course, fast) in both.images {
        XCTAssertEqual(course, fast, "\(name) \(output)")
      }
    }
  }

  /// Inside a Transform of a text scene the disc is read as in a Group
  /// (it was refused: "expected a transform operation or an object"), and
  /// both engines draw it moved: the same pixels as the disc written at
  /// its moved centre.
  func testDisc_InsideATransform() throws {
    let options = SceneOptions(style: .course, shapes: [Self.discKind])
    let moved = Self.text.replacingOccurrences(
      of: "Disc { radius 2.5 normal 0 0 1 center 0 0 0 }",
      with: "Transform { Translate 0.5 0 0 "
        + "Disc { radius 2.5 normal 0 0 1 center 0 0 0 } }")
    let placed = Self.text.replacingOccurrences(
      of: "center 0 0 0", with: "center 0.5 0 0")
    XCTAssertNotEqual(moved, Self.text)
    let a = BothEngines(
      try SceneReader.parse(
        bytes: Array(moved.utf8), file: "t.txt", options: options),
      width: 48, height: 36, style: .course)
    let b = BothEngines(
      try SceneReader.parse(
        bytes: Array(placed.utf8), file: "p.txt", options: options),
      width: 48, height: 36, style: .course)
    for ((output, course, fast), (_, placedCourse, _)) in zip(
      a.images, b.images)
    {
      XCTAssertEqual(course, fast, "\(output): both engines")
      XCTAssertEqual(course, placedCourse, "\(output): moved as placed")
    }
  }

  /// A reader without the disc's kind does not know the word; a disc
  /// without a field, or with values its kind refuses, is one error line
  /// at its place.
  func testDisc_Errors() {
    func message(_ source: String, shapes: [ShapeKind] = [Self.discKind])
      -> String
    {
      do {
        _ = try SceneReader.parse(
          bytes: Array(source.utf8), file: "d.txt",
          options: SceneOptions(style: .course, shapes: shapes))
        return "no error"
      } catch { return error.description }
    }
    let unknown = message(Self.text, shapes: [])
    XCTAssertTrue(
      unknown.hasPrefix("d.txt:12:3: error: expected an object, found 'Disc'"),
      unknown)
    let missing = message(
      Self.text.replacingOccurrences(of: "radius 2.5 ", with: ""))
    XCTAssertEqual(missing, "d.txt:12:36: error: Disc is missing 'radius'")
    let refused = message(
      Self.text.replacingOccurrences(of: "radius 2.5", with: "radius -1"))
    XCTAssertEqual(
      refused, "d.txt:12:3: error: Disc: 'radius' must be positive")
    let twice = message(
      Self.text.replacingOccurrences(
        of: "radius 2.5", with: "radius 1 radius 2"))
    XCTAssertTrue(twice.contains("'radius' is given twice in Disc"), twice)
  }
}
