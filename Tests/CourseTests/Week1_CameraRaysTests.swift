import Geometry
import SceneDescription
import XCTest

@testable import Course

/// Week 1, camera and planes: the ray of a pixel (`View.ray`). It starts at
/// the eye and goes through the pixel's screen point (x, y), where the
/// image style puts the pixel's centre on the screen [−1, 1]²
/// (`RenderSettings.screen`, given): along x·u + (H/W)·y·v + D·w, with u,
/// v, w the camera's basis (right, up, forward) and D = 1/tan(angle/2),
/// normalised so that t is a distance.
final class Week1_CameraRaysTests: XCTestCase {
  /// An eye at (1, 2, 3) looking down −z with y up: u = x, v = y, w = −z.
  func view(
    width: Int = 5, height: Int = 3, style: ImageStyle, angle: Double = 90
  ) throws -> View {
    let camera = try XCTUnwrap(
      PerspectiveCamera(
        center: Vector3(1, 2, 3), direction: Vector3(0, 0, -1),
        up: Vector3(0, 1, 0), angle: angle))
    return View(
      Scene(camera: camera, root: SceneDescription.Group([])), textures: [],
      settings: RenderSettings(
        width: width, height: height, outputs: [.depth], style: style))
  }

  func testRay_StartsAtTheEye() throws {
    for style in ImageStyle.allCases {
      let view = try view(style: style)
      for row in 0..<3 {
        for column in 0..<5 {
          XCTAssertEqual(
            view.ray(column: column, row: row).origin, Vector3(1, 2, 3),
            "\(style) (\(column), \(row))")
        }
      }
    }
  }

  /// Every pixel of a 5×3 image, in both styles: the unit vector along
  /// (x, (H/W)·y, −D). Each component within 4 ε: the same vector
  /// normalised two ways (a division, or a reciprocal and products) from
  /// a sum of three terms, each way a few roundings of numbers below 2.
  func testRay_ThroughThePixelsScreenPoint() throws {
    for style in ImageStyle.allCases {
      for angle in [30.0, 90, 120] {
        let view = try view(style: style, angle: angle)
        let screen = view.settings.screen
        let focal = view.camera.focalDistance
        for row in 0..<3 {
          for column in 0..<5 {
            let x: Double = screen.x(column: column)
            let y: Double = screen.y(row: row)
            assertClose(
              view.ray(column: column, row: row).direction,
              Vector3(x, 3.0 / 5 * y, -focal).normalized(), epsilons: 4,
              "two normalisations of the same sum allow "
                + "(\(style), angle \(angle), pixel (\(column), \(row)))")
          }
        }
      }
    }
  }

  /// In the mit style, the middle pixel of an image of odd size sits at the
  /// screen's centre: it looks straight ahead.
  func testRay_MiddlePixel_LooksAhead() throws {
    let view = try view(style: .mit)
    assertClose(
      view.ray(column: 2, row: 1).direction, Vector3(0, 0, -1), epsilons: 2,
      "normalising (0, 0, −D) allows")
  }

  /// In the mit style, the first and last columns of the middle row are the
  /// screen's left and right edges: the rays through them are the angle
  /// apart. Their cosine within 8 ε: D = 1/tan(angle/2) is two roundings,
  /// each direction a normalisation, the dot product three more, all of
  /// numbers below 2 whose cosine is not small.
  func testRay_EdgesSpanTheFieldOfView() throws {
    for (angle, cosine) in [(60.0, 0.5), (90, 0), (120, -0.5)] {
      let view = try view(style: .mit, angle: angle)
      let left = view.ray(column: 0, row: 1).direction
      let right = view.ray(column: 4, row: 1).direction
      XCTAssertEqual(
        left.dot(right), cosine, accuracy: 8 * .ulpOfOne,
        "the rays through the screen's edges are \(angle)° apart")
    }
  }

  /// Columns go right (+x), rows go down (−y), in both styles.
  func testRay_ColumnsGoRight_RowsGoDown() throws {
    for style in ImageStyle.allCases {
      let view = try view(width: 4, height: 4, style: style)
      for index in 0..<3 {
        XCTAssertLessThan(
          view.ray(column: index, row: 1).direction.x,
          view.ray(column: index + 1, row: 1).direction.x, "\(style)")
        XCTAssertGreaterThan(
          view.ray(column: 1, row: index).direction.y,
          view.ray(column: 1, row: index + 1).direction.y, "\(style)")
      }
    }
  }
}
