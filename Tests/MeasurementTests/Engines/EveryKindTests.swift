import Course
import FastEngine
import Geometry
import SceneDescription
import SceneIO
import XCTest

/// One object of every kind a scene holds (`SceneObjectKind.allCases`),
/// alone in front of the camera, drawn by both engines: each must draw it,
/// and they must agree (the bound of `EngineAgreementTests`). A new kind
/// joins the list and fails to compile here until it has an example, then
/// fails until both engines draw it.
final class EveryKindTests: XCTestCase {
  typealias Object = SceneObject<Double>

  /// An example of `kind` about the origin, seen by `camera`.
  static func example(_ kind: SceneObjectKind) -> Object {
    let corners = (
      Vector3<Double>(-1.5, -1, 0), Vector3<Double>(1.5, -1, 0),
      Vector3<Double>(0, 1.5, 0.5)
    )
    switch kind {
    case .sphere:
      return .sphere(SceneDescription.Sphere(center: .zero, radius: 1.5))
    case .plane:
      // Tilted, so that its depth varies across the image.
      return .plane(
        SceneDescription.Plane(normal: Vector3(0, 1, 1), offset: -1))
    case .triangle:
      return .triangle(
        SceneDescription.Triangle(corners.0, corners.1, corners.2))
    case .mesh:
      return .mesh(
        SceneDescription.TriangleMesh([
          SceneDescription.Triangle(corners.0, corners.1, corners.2),
          SceneDescription.Triangle(
            corners.0, Vector3(0, -2, -1), corners.1),
        ]))
    case .group:
      return .group(SceneDescription.Group([example(.sphere)]))
    case .transform:
      // Not a similarity: the sphere becomes an ellipsoid.
      return .transform(
        SceneDescription.Transform(
          matrix: .scale(Vector3(1.5, 0.75, 1)), object: example(.sphere))!)
    case .shape:
      return .shape(
        Shape(
          ShapeOfYourOwnTests.Disc(
            center: .zero, normal: Vector3(0, 0, 1), radius: 1.5,
            materialIndex: 0)))
    }
  }

  func scene(_ object: Object) throws -> Scene {
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0.25, 0.5, 8), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: 40))
    return Scene(
      camera: camera,
      lights: [
        .directional(direction: Vector3(-1, -1, -1), color: Vector3(1, 1, 1))
      ],
      materials: [Material(diffuse: Vector3(0.8, 0.6, 0.4))],
      root: SceneDescription.Group([object]))
  }

  func testEveryKind_DrawnByBothEngines() throws {
    XCTAssertEqual(
      Set(SceneObjectKind.allCases.map { Self.example($0).kind }),
      Set(SceneObjectKind.allCases), "each example is of its own kind")
    for kind in SceneObjectKind.allCases {
      let both = BothEngines(
        try scene(Self.example(kind)), width: 48, height: 48, style: .course)
      let name = kind.name
      let courseHits = both.course.depth.filter(\.isFinite).count
      let fastHits = both.fast.depth.filter(\.isFinite).count
      XCTAssertGreaterThan(
        courseHits, 48, "\(name): the course engine draws it")
      XCTAssertGreaterThan(fastHits, 48, "\(name): the fast engine draws it")
      for (output, course, fast) in both.images {
        XCTAssertGreaterThanOrEqual(
          shareWithin(
            EngineAgreementTests.levels, course, fast),
          EngineAgreementTests.share, "\(name): \(output) in both engines")
      }
    }
  }
}
