import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Pipeline
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Refusals that are true of the scene: judged from the eye, naming the
/// lengths that decide them, and for the engine that cannot draw it.
extension LengthScaleEyeTests {
  /// One object seen from an eye at (x, 0, 0) looking down −z.
  func scene(eye x: Double, _ object: SceneObject<Double>) throws -> Scene {
    Scene(
      camera: try XCTUnwrap(
        PerspectiveCamera(
          center: Vector3(x, 0, 0), direction: Vector3(0, 0, -1),
          up: Vector3(0, 1, 0), angle: 45)),
      root: Group([object]))
  }

  /// A sphere of radius r, `distance` straight ahead of an eye at x.
  func sphere(eye x: Double, radius r: Double, at distance: Double) throws
    -> Scene
  {
    try scene(
      eye: x, .sphere(Sphere(center: Vector3(x, 0, -distance), radius: r)))
  }

  /// Refused only for what the eye sees: a speck of 1e-25 three units from
  /// the eye in float (brought near 1 with its distance, its radius squared
  /// is 10⁻⁵⁰), wherever the eye is, and named by that distance; the
  /// speck three radii from the eye, wherever the eye is, is drawn.
  func testProblem_JudgedFromTheEye() throws {
    for x in [0, 1, 1e14, 1e30] {
      XCTAssertEqual(
        LengthScale.problem(
          try sphere(eye: x, radius: 1e-25, at: 3), precision: .float),
        "a sphere of radius 1e-25 (centre \(x) 0.0 -3.0) is too small "
          + "beside its distance from the eye (3.0) for float: with that "
          + "length scaled to about 1, its radius squared is below float's "
          + "normal range")
      XCTAssertNil(
        LengthScale.problem(
          try sphere(eye: x, radius: 1e-25, at: 3e-25), precision: .float),
        "eye at \(x)")
    }
    for x in [0, 1, 1e200, 1e300] {
      XCTAssertEqual(
        LengthScale.problem(
          try sphere(eye: x, radius: 1e-160, at: 3), precision: .double),
        "a sphere of radius 1e-160 (centre \(x) 0.0 -3.0) is too small "
          + "beside its distance from the eye (3.0) for double: with that "
          + "length scaled to about 1, its radius squared is below "
          + "double's normal range")
      XCTAssertNil(
        LengthScale.problem(
          try sphere(eye: x, radius: 1e-200, at: 3e-200), precision: .double),
        "eye at \(x)")
    }
  }

  /// A triangle and an ellipsoid too small beside their distance from the
  /// eye are named with the lengths that decide it; a degenerate triangle,
  /// never hit, is not refused however small.
  func testProblem_TriangleAndEllipsoidNamedByTheirLengths() throws {
    // The eye 1e14 along its view: 1e14 − 4 is exact.
    let z = 1e14
    func triangle(_ c: Vector3<Double>) throws -> Scene {
      Scene(
        camera: try XCTUnwrap(
          PerspectiveCamera(
            center: Vector3(0, 0, z), direction: Vector3(0, 0, -1),
            up: Vector3(0, 1, 0), angle: 45)),
        root: Group([
          .triangle(
            Triangle(
              Vector3(-1e-25, -1e-25, z - 4), Vector3(1e-25, -1e-25, z - 4),
              c, materialIndex: 0))
        ]))
    }
    XCTAssertEqual(
      LengthScale.problem(
        try triangle(Vector3(0, 1e-25, z - 4)), precision: .float),
      "a triangle (vertices -1e-25 -1e-25 99999999999996.0, 1e-25 -1e-25 "
        + "99999999999996.0, 0.0 1e-25 99999999999996.0) is too small beside "
        + "its distance from the eye (up to 4.0) for float: with that length "
        + "scaled to about 1, its longest edge (2.2360679774997897e-25) "
        + "squared is below float's normal range")
    XCTAssertNil(
      LengthScale.problem(
        try triangle(Vector3(0, -1e-25, z - 4)), precision: .float),
      "degenerate")
    let ellipsoid = try scene(
      eye: 1,
      .transform(
        try XCTUnwrap(
          Transform(
            matrix: .translation(Vector3(1, 0, -4))
              * .scale(Vector3(1e-25, 2e-25, 1e-25)),
            object: .sphere(Sphere(center: .zero, radius: 1))))))
    XCTAssertEqual(
      LengthScale.problem(ellipsoid, precision: .float),
      "a transformed sphere whose shortest axis is 1e-25 is too small beside "
        + "its distance from the eye (4.0) for float: with that length "
        + "scaled to about 1, its shortest axis squared is below float's "
        + "normal range")
  }

  /// The course engine computes with the scene's own lengths: what it
  /// cannot hold is refused for it, named so, and not for the fast engine.
  func testUnscaledProblem_WhatTheCourseEngineCannotHold() throws {
    let speck = try sphere(eye: 1, radius: 1e-200, at: 3e-200)
    XCTAssertNil(LengthScale.problem(speck, precision: .double))
    XCTAssertEqual(
      CourseEngineLimits.problem(speck),
      "the course engine, which computes with the scene's own lengths, "
        + "cannot draw a sphere of radius 1e-200 (centre 1.0 0.0 -3e-200): "
        + "its radius squared is below double's normal range")
    let far = try sphere(eye: 0, radius: 1e200, at: 3e200)
    XCTAssertNil(LengthScale.problem(far, precision: .double))
    XCTAssertEqual(
      CourseEngineLimits.problem(far),
      "the course engine, which computes with the scene's own lengths, "
        + "cannot draw a sphere of radius 1e+200 (centre 0.0 0.0 -3e+200): "
        + "the square of its distance from the eye (3e+200) is beyond "
        + "double's range")
    // Its eye in its own space 10¹⁶⁰ radii away: |M⁻¹·o|² overflows.
    let thin = try scene(
      eye: 0,
      .transform(
        try XCTUnwrap(
          Transform(
            matrix: .translation(Vector3(0, 0, -1e60))
              * .scale(Vector3(1e-100, 2e-100, 1e-100)),
            object: .sphere(Sphere(center: .zero, radius: 1))))))
    // The fast engine's test in the frame of the ellipsoid's axes squares
    // the same ratio (10³²⁰): refused for it too, whatever the scale.
    XCTAssertEqual(
      LengthScale.problem(thin, precision: .double),
      "a transformed sphere whose shortest axis is 1e-100 is too small "
        + "beside its distance from the eye (1e+60) for double: its "
        + "shortest axis over that distance, squared, is below double's "
        + "normal range at any scale")
    XCTAssertEqual(
      CourseEngineLimits.problem(thin),
      "the course engine, which computes with the scene's own lengths, "
        + "cannot draw a transformed sphere whose shortest axis is 1e-100: "
        + "the square of its reach from the eye (1e+60 on an axis) over its "
        + "shortest axis is beyond double's range")
    // An eye far from the origin is no problem for Double's own lengths.
    XCTAssertNil(
      CourseEngineLimits.problem(try Self.view(eye: 1e14, scale: 1)))
    XCTAssertNil(
      CourseEngineLimits.problem(try Self.view(eye: 1e300, scale: 1)))
  }

  /// An ellipsoid whose centre is more than 2⁶¹ (float) or 2⁵⁰⁹ (double)
  /// of its shortest semi-axes from the eye: its test in the frame of its
  /// axes squares that ratio, which no scale changes, so it is refused
  /// (it was left out of the image without a word); just inside, drawn.
  func testProblem_EllipsoidTooFarForItsThinnestAxis() throws {
    for (precision, limit) in [(Precision.float, 0x1p61), (.double, 0x1p509)] {
      for (ratio, refused) in [(limit * 2, true), (limit / 4, false)] {
        let distance = 1e3
        let matrix =
          Matrix4<Double>.translation(Vector3(0, 0, -distance))
          * Matrix4.scale(Vector3(100, 100, distance / ratio))
        let object = SceneObject<Double>.transform(
          try XCTUnwrap(
            Transform(
              matrix: matrix,
              object: .sphere(Sphere(center: .zero, radius: 1)))))
        let problem = LengthScale.problem(
          try scene(eye: 0, object), precision: precision)
        XCTAssertEqual(problem != nil, refused, "\(precision) \(ratio)")
        if refused {
          XCTAssertTrue(
            problem?.contains("its shortest axis over that distance") == true,
            problem ?? "")
        }
      }
    }
  }
}
