import Course
import SceneModel
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
      SceneModel.Transform<Double>(
        matrix: .translation(Vector3(2, 2, 1)) * .scale(Vector3(1, 0.3, 1)),
        object: .shape(Shape(disc))))
    return Scene(
      camera: camera,
      materials: [
        Material(diffuse: Vector3(1, 1, 1)), Material(diffuse: Vector3(1, 0, 0)),
      ],
      root: SceneModel.Group([
        .sphere(SceneModel.Sphere(center: Vector3(1, 0, 2), radius: 1)),
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
}
