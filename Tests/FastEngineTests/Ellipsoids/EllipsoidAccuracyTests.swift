import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The fast engine's ellipsoids against the exact intersection of the very
/// same camera rays (`ExactEllipsoid`, exact rational arithmetic in world
/// space, `EllipsoidAccuracy.measure`), pixel by pixel, for flat discs of
/// aspect 10⁶ to 10¹⁷ in Float and 10⁶ to 10¹⁵⁰ in Double, seen face-on
/// from near and far, at 45° and 80°, turned by rotations (before the
/// scale, after it, and on both sides), from just above the surface far
/// from the centre and from inside, and for the mild ellipsoids of the
/// project's scenes.
///
/// Bounds, and why:
/// - hit or miss: no disagreement off the rim. The rim is the pixels whose
///   ray is within 4 roundings of the silhouette: |Δ| ≤ 4 ε times the
///   exact discriminant's first-order change when the direction moves by
///   |d| or the eye's offset C − E by its own component along each of the
///   ellipsoid's axes (`ExactEllipsoid.Result.rimDistance`). The camera
///   grids put no pixel there; rays aimed at the rim itself
///   (`testNearTheRim`) disagree only within 0.32 roundings of it.
/// - reversed normals: none off the rim. On it the exact normal turns
///   through 180° within the ray's rounding, as t moves with its square
///   root (measured: one of 117 rim rays of a disc of aspect 10¹⁶).
/// - t: |t − t*| ≤ 4 ε·t*·max(1, κ_t), κ_t the relative change of t* per
///   relative change of the direction or the eye's offset (measured where
///   the error exceeds 4 ε). The frame's test rounds a few times after
///   cancellation-free steps: measured ≤ 2.1 ε without κ on every disc,
///   where the object-space test it replaces lost hits from 10⁶ on and
///   every hit at 10¹⁷ (Float) and 10¹⁵⁰ (Double).
/// - normal: the angle ≤ 4 ε·max(1, κ_n), κ_n the angle's change per
///   relative change of the direction or the eye's offset. Flat discs
///   measure ≤ 1.1 ε without κ; ellipsoids tens of radii away, like far
///   spheres, measure up to 300 ε raw (ε times the distance in radii),
///   within 4 ε·κ_n.
final class EllipsoidAccuracyTests: XCTestCase {
  /// The images' size: 16 pixels square with RAYTRACE_LONG_TESTS (CI), 12
  /// in a student's `swift test`.
  static let size = runsLongTests ? 16 : 12

  /// A disc of aspect 10^exponent: the unit sphere scaled by
  /// s = 10^⌊exponent/2⌋ across and 10^−⌈exponent/2⌉ through, seen from
  /// places given in units of its radius s, six views.
  static func discs(aspect exponent: Int) -> [EllipsoidCase] {
    let wide = "1e\(exponent / 2)"
    let thin = "1e-\(exponent - exponent / 2)"
    let r = pow(10, Double(exponent / 2))
    let scale = "Scale \(wide) \(wide) \(thin)"
    return [
      EllipsoidCase(
        name: "1e\(exponent) face-on near", operations: [scale],
        eye: (0.1 * r, 0.05 * r, 1.5 * r), direction: (0, 0, -1)),
      EllipsoidCase(
        name: "1e\(exponent) face-on far", operations: [scale],
        eye: (0, 0, 4 * r), direction: (0, 0, -1)),
      EllipsoidCase(
        name: "1e\(exponent) at 45°", operations: [scale],
        eye: (0.2 * r, -2 * r, 2 * r), direction: (0, 1, -1), up: (0, 0, 1)),
      EllipsoidCase(
        name: "1e\(exponent) at 80°", operations: [scale],
        eye: (0.1 * r, -3 * r, 0.55 * r), direction: (0, 1, -0.18),
        up: (0, 0, 1)),
      EllipsoidCase(
        name: "1e\(exponent) rotated",
        operations: [
          "XRotate 30", "ZRotate 20", scale,
        ],
        eye: (0.3 * r, -1.4 * r, 2.6 * r), direction: (-0.2, 0.5, -1)),
      EllipsoidCase(
        name: "1e\(exponent) rotated, then scaled",
        operations: [
          scale, "XRotate 30", "ZRotate 20",
        ],
        eye: (0.2 * r, -0.3 * r, 2 * r), direction: (-0.1, 0.1, -1)),
    ] + more(aspect: exponent)
  }

  /// Three views more: a turned disc seen from just above its surface far
  /// from its centre (where turning its axes by ε would move the surface
  /// by ε·|C − E|, far more than ε·t), the eye inside a disc, and a disc
  /// scaled between two rotations.
  static func more(aspect exponent: Int) -> [EllipsoidCase] {
    let wide = "1e\(exponent / 2)"
    let thinExponent = exponent - exponent / 2
    let thin = "1e-\(thinExponent)"
    let r = pow(10, Double(exponent / 2))
    let h = pow(10, -Double(thinExponent))
    let scale = "Scale \(wide) \(wide) \(thin)"
    // Off both axes in the disc's plane and at angles whose sines and
    // cosines all round: a tilt of the axes by their rounding moves the
    // surface under the eye.
    let turn = Matrix4<Double>.rotationX(degrees: 37) * .rotationZ(degrees: 23)
    let above = turn.transformPoint(Vector3(0.5 * r, 0.5 * r, 0.02 * r))
    let down = turn.transformDirection(Vector3(-0.4, -0.3, -1))
    return [
      EllipsoidCase(
        name: "1e\(exponent) rotated, from just above",
        operations: [
          "XRotate 37", "ZRotate 23", scale,
        ],
        eye: (above.x, above.y, above.z), direction: (down.x, down.y, down.z)),
      EllipsoidCase(
        name: "1e\(exponent) from inside", operations: [scale],
        eye: (0.2 * r, 0.1 * r, 0.5 * h), direction: (1, 0.3, 0),
        up: (0, 0, 1), angle: 60),
      EllipsoidCase(
        name: "1e\(exponent) between rotations",
        operations: [
          "XRotate 30", scale, "ZRotate 20",
        ],
        eye: (0.3 * r, -1.4 * r, 2.6 * r), direction: (-0.2, 0.5, -1)),
    ]
  }

  /// Ellipsoids of aspect 8 or less, as the project's scenes hold
  /// (mesh-and-transforms, the course's C03), near and far; those within
  /// 64 radii keep the object-space test in Float (`StableEllipsoid`).
  static let mild = [
    EllipsoidCase(
      name: "mesh-and-transforms",
      operations: [
        "Translate 2.2 0 0.5", "ZRotate 25", "Scale 1.6 0.6 1",
      ],
      eye: (0, 3, 11), direction: (0.2, -0.25, -1), angle: 20),
    EllipsoidCase(
      name: "C03", operations: ["ZRotate 45", "Scale 1 0.2 1"],
      eye: (0, 0, 10), direction: (0, 0, -1), angle: 20),
    EllipsoidCase(
      name: "aspect 8, 1.5 radii", operations: ["XRotate 10", "Scale 4 2 0.5"],
      eye: (0.3, 0.2, 0.75), direction: (0, 0, -1), angle: 90),
    EllipsoidCase(
      name: "aspect 8, 60 radii", operations: ["YRotate 10", "Scale 4 2 0.5"],
      eye: (0.3, 0.2, 30), direction: (0, 0, -1), angle: 10),
    EllipsoidCase(
      name: "aspect 8, 70 radii", operations: ["YRotate 10", "Scale 4 2 0.5"],
      eye: (0.3, 0.2, 35), direction: (0, 0, -1), angle: 10),
  ]

  /// Renders each case at `size`×`size` in R and holds it to the bounds
  /// above; prints each measurement when `printing`.
  func check<R: RayScalar>(
    _ cases: [EllipsoidCase], _: R.Type,
    size: Int = EllipsoidAccuracyTests.size,
    printing: Bool = false
  ) throws {
    for test in cases {
      let measured = try EllipsoidAccuracy.measure(
        test, R.self, width: size, height: size)
      let label = "\(R.self) \(test): \(measured)"
      if printing {
        // To standard error, unbuffered: standard output lost the first
        // lines of this long a run.
        FileHandle.standardError.write(Data((label + "\n").utf8))
      }
      XCTAssertGreaterThan(measured.interiorHits, 0, label)
      XCTAssertEqual(measured.disagreements, 0, label)
      XCTAssertLessThanOrEqual(measured.tError, 4, label)
      XCTAssertLessThanOrEqual(measured.normalError, 4, label)
      XCTAssertEqual(measured.reversed, 0, label)
    }
  }

  /// The issue's rows: Scale 1e3 1e3 1e-3 (aspect 10⁶) and aspect 10⁸ in
  /// Float, which lost 14 and 148 of 520 pixels of a face-on disc and
  /// reversed normals.
  /// (Aspect 10⁸ only, unless RAYTRACE_LONG_TESTS: it is the harder.)
  func testFlatDiscs_Float() throws {
    try check(
      (runsLongTests ? Self.discs(aspect: 6) : [])
        + Self.quickCases(Self.discs(aspect: 8)), Float.self)
  }

  /// The issue's aspect 10¹⁶ in Double (260 of 520 pixels lost), and the
  /// thinnest Double holds here, 10¹⁵⁰.
  func testFlatDiscs_Double() throws {
    try check(Self.quickCases(Self.discs(aspect: 16), half: 1), Double.self)
    try check(Self.quickCases(Self.more(aspect: 150)), Double.self)
  }

  func testMildEllipsoids() throws {
    try check(Self.quickCases(Self.mild), Float.self)
    try check(Self.quickCases(Self.mild, half: 1), Double.self)
  }

  /// Rays aimed within 2⁻⁴ to 2⁻⁵⁶ of the rim, inside and out, of discs
  /// face-on and turned, in both precisions: some fall on the rim, where
  /// hit or miss and the normal's side may go either way; none off it may
  /// disagree, and the hits off it hold the bounds of t and normal.
  /// (A turned disc in each precision unless RAYTRACE_LONG_TESTS.)
  func testNearTheRim() throws {
    let cases =
      (runsLongTests ? [(Self.discs(aspect: 8)[1], false)] : [])
      + [(Self.discs(aspect: 8)[4], false), (Self.discs(aspect: 16)[2], true)]
      + (runsLongTests ? [(Self.discs(aspect: 150)[4], true)] : [])
    for (test, double) in cases {
      let measured =
        try double
        ? EllipsoidAccuracy.measureRim(test, Double.self)
        : EllipsoidAccuracy.measureRim(test, Float.self)
      let label =
        "\(double ? "Double" : "Float") \(test), near the rim: "
        + "\(measured)"
      XCTAssertGreaterThan(measured.rim, 0, label)
      XCTAssertGreaterThan(measured.interiorHits, 0, label)
      XCTAssertEqual(measured.disagreements, 0, label)
      XCTAssertLessThanOrEqual(measured.tError, 4, label)
      XCTAssertLessThanOrEqual(measured.normalError, 4, label)
      XCTAssertEqual(measured.reversed, 0, label)
      FileHandle.standardError.write(Data((label + "\n").utf8))
    }
  }

  /// Every aspect and view at 32×32, printed: the table of
  /// docs/ACCURACY.md.
  func testEveryAspectAndView() throws {
    try skipUnlessLongTests()
    try check(Self.mild, Float.self, size: 32, printing: true)
    for exponent in [6, 8, 12, 17] {
      try check(
        Self.discs(aspect: exponent), Float.self, size: 32, printing: true)
    }
    try check(Self.mild, Double.self, size: 32, printing: true)
    for exponent in [6, 16, 30, 100, 150] {
      try check(
        Self.discs(aspect: exponent), Double.self, size: 32, printing: true)
    }
  }
}
