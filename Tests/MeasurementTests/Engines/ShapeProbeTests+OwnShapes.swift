import Course
import Measurement
import Geometry
import SceneDescription
import XCTest

/// A disc of the test's own (docs/ADDING-A-SHAPE.md), right or with one
/// mistake: the probes do not know it, and check what any `Hittable` must
/// do.
struct ProbedDisc: Hittable {
  enum Mistake {
    case none, normalTwice, boxTooSmall, tAlongUnitDirection, tMinOnly
  }

  var radius = 2.5
  var mistake = Mistake.none
  var hasBox = true

  func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    let normal = Vector3<Double>(0, 0, 1)
    let d =
      mistake == .tAlongUnitDirection
      ? ray.direction.normalized() : ray.direction
    let t = -normal.dot(ray.origin) / normal.dot(d)
    guard tMin < t, mistake == .tMinOnly || t < tMax,
      (ray.origin + d * t).lengthSquared <= radius * radius
    else { return nil }
    return Hit(
      t: t, normal: mistake == .normalTwice ? normal * 2 : normal,
      materialIndex: 0)
  }

  var boundingBox: BoundingBox? {
    guard hasBox else { return nil }
    let reach = mistake == .boxTooSmall ? radius / 2 : radius
    return BoundingBox(
      lower: Vector3(-reach, -reach, -reach),
      upper: Vector3(reach, reach, reach))
  }
}

extension ShapeProbeTests {
  func own(_ disc: ProbedDisc) -> ShapeProbeReport {
    ShapeProbes.probe([], own: [Shape(disc)])
  }

  func testOwnShape_SaidAndChecked() throws {
    for hasBox in [true, false] {
      let report = own(ProbedDisc(hasBox: hasBox))
      XCTAssertTrue(report.passes, report.lines.joined(separator: "\n"))
      XCTAssertEqual(report.lines.count, 1)
      let line = try XCTUnwrap(report.lines.first)
      XCTAssertTrue(
        line.hasPrefix(
          "ProbedDisc: a shape of one's own, which the probes do not know"),
        line)
      XCTAssertTrue(line.contains("with 48 rays"), line)
      XCTAssertFalse(line.contains("none hit"), line)
    }
  }

  /// Shapes of one's own are found in groups and under transforms, each
  /// checked once however often the scene holds it.
  func testOwnShape_FoundInTheScene() throws {
    let disc = Shape(ProbedDisc())
    let moved = try XCTUnwrap(
      SceneDescription.Transform<Double>(
        matrix: .translation(Vector3(2, 2, 1)),
        object: .group(SceneDescription.Group([.shape(Shape(ProbedDisc()))]))))
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0, 0, 10), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 40))
    let scene = Scene(
      camera: camera,
      root: SceneDescription.Group([
        .shape(disc), .transform(moved), .shape(disc),
      ]))
    let report = ShapeProbes.check(scene)
    XCTAssertTrue(report.passes, report.lines.joined(separator: "\n"))
    XCTAssertEqual(report.probed.map(\.name), ["Sphere", "Transform"])
    XCTAssertTrue(
      report.notes.contains {
        $0.contains("ProbedDisc") && $0.contains("all 2")
      },
      report.lines.joined(separator: "\n"))
  }

  func testOwnShape_NormalNotUnit() {
    assertNames(
      own(ProbedDisc(mistake: .normalTwice)), .ownNormalNotUnit,
      "the normal has length 2.0, not 1")
  }

  func testOwnShape_HitOutsideItsBox() {
    assertNames(
      own(ProbedDisc(mistake: .boxTooSmall)), .ownHitOutsideBox,
      "outside its bounding box")
  }

  /// t counted along the unit direction: the point lands three times as
  /// far (the rays' directions have length 3), outside the box; without a
  /// box, the second ray along the same line does not find it again.
  func testOwnShape_TNotAlongTheRay() {
    assertNames(
      own(ProbedDisc(mistake: .tAlongUnitDirection)), .ownHitOutsideBox,
      "|d| = 3")
    assertNames(
      own(ProbedDisc(mistake: .tAlongUnitDirection, hasBox: false)),
      .ownTAlongRay, "should find the same point")
  }

  func testOwnShape_HitBeyondTMax() {
    assertNames(
      own(ProbedDisc(mistake: .tMinOnly)), .ownOutsideInterval,
      "asked for a hit before tMax")
  }
}
