import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

final class CameraTests: XCTestCase {
  // MARK: - Basis

  /// u, v, w unit length and mutually perpendicular, with u = w × up
  /// (right), v on the side of up, and u × v = −w (a right-handed frame
  /// looking down −w). Random directions and ups at least 1e−3 rad from
  /// parallel.
  func checkBasis<T: RayScalar>(_: T.Type, base: UInt64) {
    let epsilon = Double(T.ulpOfOne)
    forEachSeed(1000, base: base) { generator, seed in
      let direction =
        generator.unitVector(T.self) * generator.logUniform(1e-3, 1e3)
      var up = generator.unitVector(T.self) * generator.logUniform(1e-3, 1e3)
      while Double(direction.normalized().cross(up.normalized()).length) < 1e-3
      {
        up = generator.unitVector(T.self)
      }
      guard
        let camera = PerspectiveCamera(
          center: generator.unitVector(T.self), direction: direction, up: up,
          angle: 45)
      else {
        XCTFail("seed \(seed): a valid camera")
        return
      }
      let (u, v, w) = (camera.horizontal, camera.up, camera.direction)
      // Each is a normalised vector: |x| − 1 within 2 ulps (component
      // roundings and the square root).
      for (name, vector) in [("u", u), ("v", v), ("w", w)] {
        XCTAssertEqual(
          Double(vector.length), 1, accuracy: 2 * epsilon,
          "seed \(seed): |\(name)|")
      }
      // Dot products of unit vectors: a few roundings of terms ≤ 1 (u is
      // normalised after the cross product, so its error does not grow
      // with 1/sin(direction, up)): measured worst 2ε; budget 4ε.
      XCTAssertEqual(
        Double(u.dot(v)), 0, accuracy: 4 * epsilon, "seed \(seed): u·v")
      XCTAssertEqual(
        Double(u.dot(w)), 0, accuracy: 4 * epsilon, "seed \(seed): u·w")
      XCTAssertEqual(
        Double(v.dot(w)), 0, accuracy: 4 * epsilon, "seed \(seed): v·w")
      XCTAssertEqual(
        w, direction.normalized(), "seed \(seed): w = direction/|direction|")
      XCTAssertGreaterThan(v.dot(up), 0, "seed \(seed): v on the side of up")
      // A cross product of two unit vectors, each ≤ 2 ulps off: measured
      // worst 2.3 ulps of the largest component; budget 4.
      assertRelativeError(
        u.cross(v), (-w).reference, ulps: 4,
        "seed \(seed): right-handed, u × v = −w")
    }
  }

  func testBasis_Orthonormal_Float() {
    checkBasis(Float.self, base: 0xCA3E_0001)
  }
  func testBasis_Orthonormal_Double() {
    checkBasis(Double.self, base: 0xCA3E_0002)
  }

  /// The usual camera: looking down −z with y up gives u = +x, v = +y.
  func testBasis_Axes() throws {
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0, 0, 8), direction: Vector3(0, 0, -3),
        up: Vector3(0, 2, 0),
        angle: 90))
    XCTAssertEqual(camera.direction, Vector3(0, 0, -1))
    XCTAssertEqual(camera.horizontal, Vector3(1, 0, 0))
    XCTAssertEqual(camera.up, Vector3(0, 1, 0))
    XCTAssertEqual(camera.center, Vector3(0, 0, 8))
    // 1/tan(45°): tan rounds, so allow 1 ulp either way.
    XCTAssertEqual(camera.focalDistance, 1, accuracy: Double.ulpOfOne)
  }

  // MARK: - Rays

  /// The centre of the screen looks along w; the edges of the screen are
  /// at the half-angle horizontally and at aspect × that vertically.
  func checkRayDirections<T: RayScalar>(_: T.Type) throws {
    let camera = try XCTUnwrap(
      PerspectiveCamera<T>(
        center: Vector3(1, 2, 3), direction: Vector3(1, -2, 0.5),
        up: Vector3(0, 1, 0),
        angle: 60))
    for aspect: T in [0.5, 1, 0.75] {
      let centre = camera.rayDirection(x: 0, y: 0, aspect: aspect)
      // (D·w)/|D·w|: two roundings per component.
      assertRelativeError(
        centre, camera.direction.reference, ulps: 2, "centre ray")
    }
    // tan(30°) = 1/√3: the ray to the right edge has (d·u)/(d·w) = 1/D.
    let tanHalf = 1 / ReferenceScalar(3).squareRoot()
    let right = camera.rayDirection(x: 1, y: 0, aspect: 0.75)
    // D from libm's tan (≤ 1 ulp), then the sum, the normalisation and
    // the two dot products and quotient here: budget 8 ulps.
    assertRelativeError(
      right.dot(camera.horizontal) / right.dot(camera.direction), tanHalf,
      ulps: 8,
      "horizontal half-angle")
    let top = camera.rayDirection(x: 0, y: 1, aspect: 0.75)
    assertRelativeError(
      top.dot(camera.up) / top.dot(camera.direction), tanHalf * 0.75, ulps: 8,
      "vertical half-angle = aspect × horizontal")
    for (x, y): (T, T) in [(-1, -1), (1, 1), (0.3, -0.7)] {
      let direction = camera.rayDirection(x: x, y: y, aspect: 0.75)
      XCTAssertEqual(
        Double(direction.length), 1, accuracy: 2 * Double(T.ulpOfOne),
        "unit ray")
      XCTAssertGreaterThan(direction.dot(camera.direction), 0, "in front")
      XCTAssertEqual(direction.dot(camera.horizontal) > 0, x > 0, "x → right")
      XCTAssertEqual(direction.dot(camera.up) > 0, y > 0, "y → up")
    }
  }

  func testRayDirection_Float() throws { try checkRayDirections(Float.self) }
  func testRayDirection_Double() throws { try checkRayDirections(Double.self) }

  /// Very narrow and very wide fields of view still give cameras.
  func testInit_ExtremeAngles() throws {
    for angle in [1e-6, 0.5, 179.5, 179.999] {
      let camera = try XCTUnwrap(
        PerspectiveCamera<Double>(
          center: .zero, direction: Vector3(0, 0, -1), up: Vector3(0, 1, 0),
          angle: angle), "angle \(angle)")
      XCTAssertTrue(camera.focalDistance.isFinite && camera.focalDistance > 0)
    }
  }

  /// No basis: nil rather than NaNs.
  func testInit_Invalid() {
    let z = Vector3<Double>(0, 0, -1)
    let y = Vector3<Double>(0, 1, 0)
    let cases: [(String, Vector3<Double>, Vector3<Double>, Double)] = [
      ("zero direction", .zero, y, 45),
      ("negative-zero direction", Vector3(-0.0, -0.0, 0), y, 45),
      ("up parallel", Vector3(0, 3, 0), y, 45),
      ("up antiparallel", Vector3(0, -1, 0), Vector3(0, 5, 0), 45),
      ("zero up", z, .zero, 45),
      ("angle 0", z, y, 0),
      ("angle 180", z, y, 180),
      ("negative angle", z, y, -30),
      ("angle over 180", z, y, 270),
      ("NaN angle", z, y, .nan),
      ("NaN direction", Vector3(.nan, 0, -1), y, 45),
      ("infinite direction", Vector3(.infinity, 0, 0), y, 45),
      ("NaN up", z, Vector3(0, .nan, 0), 45),
    ]
    for (name, direction, up, angle) in cases {
      XCTAssertNil(
        PerspectiveCamera(
          center: .zero, direction: direction, up: up, angle: angle), name)
      XCTAssertNil(
        PerspectiveCamera<Float>(
          center: .zero, direction: Vector3(direction), up: Vector3(up),
          angle: Float(angle)), "Float: \(name)")
    }
  }

  /// Converting precision rounds each stored vector once.
  func testInit_ConvertsPrecision() throws {
    let double = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: Vector3(0.1, 0.2, 0.3), direction: Vector3(1, 2, 3),
        up: Vector3(0, 1, 0),
        angle: 33))
    let float = PerspectiveCamera<Float>(double)
    XCTAssertEqual(float.center, Vector3(0.1, 0.2, 0.3))
    XCTAssertEqual(float.direction, Vector3<Float>(double.direction))
    XCTAssertEqual(float.horizontal, Vector3<Float>(double.horizontal))
    XCTAssertEqual(float.up, Vector3<Float>(double.up))
    XCTAssertEqual(float.angle, 33)
    XCTAssertEqual(float.focalDistance, Float(double.focalDistance))
  }

  // MARK: - Image conventions

  /// Course: x = (2i + 1)/W − 1 at pixel centres, y = 1 − (2j − 1)/H one
  /// pixel above them (the course's own mapping). Mit: pixel corners,
  /// x = 2i/(W − 1) − 1, and 0 for W = 1. Rows run top to bottom.
  func checkScreenCoordinates<T: RayScalar>(_: T.Type) {
    func map(_ style: ImageStyle, _ width: Int, _ height: Int) -> ScreenMap {
      ScreenMap(style: style, width: width, height: height)
    }
    let course: [T] = (0..<4).map { map(.course, 4, 1).x(column: $0) }
    XCTAssertEqual(course, [-0.75, -0.25, 0.25, 0.75], "\(T.self): exact")
    let mit: [T] = (0..<4).map { map(.mit, 4, 1).x(column: $0) }
    XCTAssertEqual(mit[0], -1, "\(T.self)")
    XCTAssertEqual(mit[3], 1, "\(T.self)")
    let courseRows: [T] = (0..<4).map { map(.course, 1, 4).y(row: $0) }
    XCTAssertEqual(
      courseRows, [1.25, 0.75, 0.25, -0.25], "\(T.self): top first, exact")
    let mitRows: [T] = (0..<3).map { map(.mit, 1, 3).y(row: $0) }
    XCTAssertEqual(mitRows, [1, 0, -1], "\(T.self): top first, exact")
    for style in ImageStyle.allCases {
      XCTAssertEqual(
        map(style, 1, 1).x(column: 0) as T, 0, "\(style) W = 1")
    }
    XCTAssertEqual(map(.mit, 1, 1).y(row: 0) as T, 0, "H = 1")
    XCTAssertEqual(
      map(.course, 1, 1).y(row: 0) as T, 2,
      "course H = 1: one pixel above the only row's centre")

    // Against the exact fractions for many sizes: one division and one
    // subtraction of values ≤ 2, so an absolute error of at most ε. The
    // course's row j is its column j's x negated and moved up one pixel.
    for width in [2, 3, 5, 7, 10, 99, 640, 1001] {
      for i in 0..<width {
        let exactCourse =
          ReferenceScalar(2 * i + 1 - width) / ReferenceScalar(width)
        let exactMit =
          ReferenceScalar(2 * i - (width - 1)) / ReferenceScalar(width - 1)
        let gotCourse: T = map(.course, width, width).x(column: i)
        let gotMit: T = map(.mit, width, width).x(column: i)
        let gotCourseRow: T = map(.course, width, width).y(row: i)
        let gotMitRow: T = map(.mit, width, width).y(row: i)
        let tolerance = ReferenceScalar(T.ulpOfOne)
        for (name, got, want) in [
          ("course x", gotCourse, exactCourse), ("mit x", gotMit, exactMit),
          (
            "course y", gotCourseRow,
            -exactCourse + 2 / ReferenceScalar(width)
          ),
          ("mit y", gotMitRow, -exactMit),
        ] {
          XCTAssertLessThanOrEqual(
            (ReferenceScalar(got) - want).magnitude, tolerance,
            "\(T.self) \(name) i = \(i) of \(width): \(got) vs \(want)")
        }
      }
    }
  }

  func testScreenCoordinates_Float() { checkScreenCoordinates(Float.self) }
  func testScreenCoordinates_Double() { checkScreenCoordinates(Double.self) }
}
