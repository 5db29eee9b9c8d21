import Geometry

/// The plane's probes and the triangle's. Each ray's answer is worked out
/// beside it.
extension ShapeProbe {
  static var planeTexts: ShapeTexts {
    ShapeTexts(
      name: "Plane",
      normalLength: {
        "the normal has length \(text($0)), not 1: return the plane's "
          + "own normal as it is"
      },
      normalTurned: "the normal is the plane's own, n, from either side: "
        + "do not turn it towards the ray",
      normalDirection: "the hit's normal is the plane's own, n, whatever "
        + "the ray")
  }

  /// Seven rays at the plane y = −2 (normal (0, 1, 0), offset −2):
  /// t = (offset − n·o) / (n·d). With the offset's sign flipped it is the
  /// plane y = 2.
  static var plane: [ShapeProbe] {
    let texts = planeTexts
    let what = "the plane y = -2 (normal (0, 1, 0), offset -2)"
    let make: (ShapeFactories) -> any Hittable = {
      $0.plane(v(0, 1, 0), -2, 0)
    }
    func offsetSign(_ t: Double) -> Mistake {
      Mistake(
        answer: .hit(t: t), cause: .offsetSign,
        says: "t = \(text(t)) reaches the plane y = 2: the offset's sign; "
          + "the plane is n·P = offset, so t = (offset − n·o) / (n·d)")
    }
    func parallel(_ say: String) -> Mistake {
      Mistake(
        answer: .anyHit, cause: .parallelHit,
        says: "a ray parallel to the plane (n·d = 0) \(say): return nil "
          + "(t = (offset − n·o) / 0 is infinite or NaN, no hit)")
    }
    let formula = "t = (offset − n·o) / (n·d)"
    return [
      // (−2 − 5) / (−1) = 7; flipped, (2 − 5) / (−1) = 3.
      ShapeProbe(
        texts: texts, id: "above", what: "\(what), from above",
        make: make, ray: ray(v(0, 5, 0), v(0, -1, 0)),
        expected: Expected(t: 7, normal: v(0, 1, 0)),
        mistakes: [offsetSign(3)], otherwise: (.formula, formula)),
      // (−2 + 5) / 1 = 3; flipped, 7.
      ShapeProbe(
        texts: texts, id: "below", what: "\(what), from below",
        make: make, ray: ray(v(0, -5, 0), v(0, 1, 0)),
        expected: Expected(t: 3, normal: v(0, 1, 0)),
        mistakes: [
          offsetSign(7),
          Mistake(
            answer: .miss, cause: .backSideMissed,
            says: "a ray from below (n·d > 0) hits too: a plane has two "
              + "sides; do not test the sign of n·d"),
        ],
        otherwise: (.formula, formula), controls: ["above"]),
      // n·d = −4: (−2 − 5) / (−4) = 1.75, the point 8.75 away; flipped,
      // 0.75.
      ShapeProbe(
        texts: texts, id: "long",
        what: "\(what), along a direction of length 5",
        make: make, ray: ray(v(0, 5, 0), v(3, -4, 0)),
        expected: Expected(t: 1.75, normal: v(0, 1, 0)),
        mistakes: [
          offsetSign(0.75),
          Mistake(
            answer: .hit(t: 8.75), cause: .directionNormalised,
            says: "t = 8.75 is the distance: the direction was normalised, "
              + "but t counts multiples of d as given (|d| = 5); do not "
              + "normalise it"),
        ],
        otherwise: (
          .directionLength,
          "\(formula), with d as given (|d| = 5), not normalised"
        ),
        controls: ["above"]),
      // (−2 + 5) / 0 = +∞.
      ShapeProbe(
        texts: texts, id: "parallel", what: "\(what), beside it",
        make: make, ray: ray(v(0, -5, 0), v(1, 0, 0)), expected: nil,
        mistakes: [parallel("never meets it")],
        otherwise: (.parallelHit, ""), controls: ["above"]),
      // 0 / 0 = NaN.
      ShapeProbe(
        texts: texts, id: "within", what: "\(what), within it",
        make: make, ray: ray(v(0, -2, 0), v(1, 0, 0)), expected: nil,
        mistakes: [parallel("within it has no single hit")],
        otherwise: (.parallelHit, ""), controls: ["above"]),
      // (−2 − 5) / 1 = −7.
      ShapeProbe(
        texts: texts, id: "behind", what: "\(what), behind the ray",
        make: make, ray: ray(v(0, 5, 0), v(0, 1, 0)), expected: nil,
        mistakes: [
          Mistake(
            answer: .anyHit, cause: .hitBehind,
            says: "the plane is behind the ray (t = −7): return nil unless "
              + "tMin < t < tMax")
        ],
        otherwise: (.hitBehind, ""), controls: ["above"]),
      ShapeProbe(
        texts: texts, id: "tMax", what: "\(what), from above",
        make: make, ray: ray(v(0, 5, 0), v(0, -1, 0)), tMax: 5,
        expected: nil,
        otherwise: (
          .hitBeyondTMax,
          "the plane is at t = 7, after tMax = 5: return nil unless "
            + "tMin < t < tMax"
        ),
        controls: ["above"]),
    ]
  }

  static var triangleTexts: ShapeTexts {
    ShapeTexts(
      name: "Triangle",
      normalLength: {
        "the normal has length \(text($0)), not 1: normalise "
          + "(b − a) × (c − a), or the interpolated normal"
      },
      normalTurned: "the normal is the winding's, (b − a) × (c − a), from "
        + "either side: not (c − a) × (b − a), and not turned towards the "
        + "ray",
      normalDirection: "the normal is (b − a) × (c − a), normalised; with "
        + "vertex normals, (1 − β − γ)·n0 + β·n1 + γ·n2, normalised")
  }

  /// Ten rays at the triangle a = (0, 0, −4), b = (4, 0, −4),
  /// c = (0, 4, −4). A ray from (x, y, 0) along (0, 0, −1) meets its
  /// plane at a + β(b − a) + γ(c − a) with β = x/4, γ = y/4, t = 4.
  static var triangle: [ShapeProbe] {
    let texts = triangleTexts
    let corners = ProbedTriangle(
      a: v(0, 0, -4), b: v(4, 0, -4), c: v(0, 4, -4))
    let what = "the triangle (0, 0, -4), (4, 0, -4), (0, 4, -4)"
    let make: (ShapeFactories) -> any Hittable = { $0.triangle(corners) }
    var smooth = corners
    smooth.normals = (v(0, 0, 1), v(1, 0, 0), v(0, 2, 0))
    smooth.textureCoordinates = (
      TextureCoordinate(0, 0), TextureCoordinate(1, 0),
      TextureCoordinate(0, 1)
    )
    let down = v(0, 0, -1)
    func outside(
      _ id: String, _ x: Double, _ y: Double, _ cause: ProbeCause,
      _ says: String
    ) -> ShapeProbe {
      ShapeProbe(
        texts: texts, id: id, what: "\(what), just outside an edge",
        make: make, ray: ray(v(x, y, 0), down), expected: nil,
        mistakes: [Mistake(answer: .anyHit, cause: cause, says: says)],
        otherwise: (cause, ""), controls: ["inside"])
    }
    return [
      ShapeProbe(
        texts: texts, id: "inside", what: what,
        make: make, ray: ray(v(1, 1, 0), down),
        expected: Expected(t: 4, normal: v(0, 0, 1)),
        otherwise: (
          .formula,
          "solve β·(b − a) + γ·(c − a) − t·d = o − a (Cramer's rule): "
            + "here β = γ = 0.25 and t = 4, inside"
        )),
      outside(
        "beta", -0.25, 1, .edgeBeta,
        "β = -0.0625 < 0: the point is outside the edge from a to c; "
          + "test β ≥ 0"),
      outside(
        "gamma", 1, -0.25, .edgeGamma,
        "γ = -0.0625 < 0: the point is outside the edge from a to b; "
          + "test γ ≥ 0"),
      outside(
        "sum", 2.25, 2.25, .edgeSum,
        "β + γ = 1.125 > 1: the point is outside the edge from b to c; "
          + "test β + γ ≤ 1"),
      ShapeProbe(
        texts: texts, id: "behind", what: "\(what), behind the ray",
        make: make, ray: ray(v(1, 1, 0), v(0, 0, 1)), expected: nil,
        mistakes: [
          Mistake(
            answer: .anyHit, cause: .hitBehind,
            says: "the triangle is behind the ray (t = −4): return nil "
              + "unless tMin < t < tMax")
        ],
        otherwise: (.hitBehind, ""), controls: ["inside"]),
      // From z = −8 upwards: β = γ = 0.25, t = 4, the winding's normal.
      ShapeProbe(
        texts: texts, id: "back", what: "\(what), from its back",
        make: make, ray: ray(v(1, 1, -8), v(0, 0, 1)),
        expected: Expected(t: 4, normal: v(0, 0, 1)),
        mistakes: [
          Mistake(
            answer: .miss, cause: .backSideMissed,
            says: "a ray from the back hits too: the determinant's sign is "
              + "no test (only 0, a ray parallel to the plane, is)")
        ],
        otherwise: (.formula, "Cramer's rule, whatever the side"),
        controls: ["inside"]),
      ShapeProbe(
        texts: texts, id: "long",
        what: "\(what), along a direction of "
          + "length 2",
        make: make, ray: ray(v(1, 1, 0), v(0, 0, -2)),
        expected: Expected(t: 2, normal: v(0, 0, 1)),
        mistakes: [
          Mistake(
            answer: .hit(t: 4), cause: .directionNormalised,
            says: "t = 4 is the distance: the direction was normalised, "
              + "but t counts multiples of d as given (|d| = 2); do not "
              + "normalise it")
        ],
        otherwise: (
          .directionLength,
          "t is not measured along the given direction (|d| = 2): solve "
            + "with d as it is"
        ),
        controls: ["inside"]),
      ShapeProbe(
        texts: texts, id: "parallel", what: "\(what), beside it",
        make: make, ray: ray(v(1, 1, 0), v(1, 0, 0)), expected: nil,
        mistakes: [
          Mistake(
            answer: .anyHit, cause: .parallelHit,
            says: "a ray parallel to the triangle's plane never meets it: "
              + "return nil when the determinant is 0")
        ],
        otherwise: (.parallelHit, ""), controls: ["inside"]),
      // β = 0.5, γ = 0.25: the normal (0.5, 0.5, 0.25) / 0.75, the
      // texture coordinate (β, γ).
      ShapeProbe(
        texts: texts, id: "smooth",
        what: "\(what) with normals (0, 0, 1), (1, 0, 0), (0, 2, 0) and "
          + "texture coordinates (0, 0), (1, 0), (0, 1)",
        make: { $0.triangle(smooth) }, ray: ray(v(2, 1, 0), down),
        expected: Expected(
          t: 4, normal: v(0.5, 0.5, 0.25).normalized(),
          texture: TextureCoordinate(0.5, 0.25)),
        mistakes: [
          Mistake(
            answer: .normal(v(0, 0, 1)), cause: .normalsNotInterpolated,
            says: "the vertex normals are not used: with normals, the "
              + "normal is (1 − β − γ)·n0 + β·n1 + γ·n2, normalised"),
          Mistake(
            answer: .noTexture, cause: .textureNotInterpolated,
            says: "no texture coordinate: with coordinates, it is "
              + "(1 − β − γ)·t0 + β·t1 + γ·t2"),
        ],
        otherwise: (.formula, "here β = 0.5, γ = 0.25 and t = 4"),
        controls: ["inside"]),
      ShapeProbe(
        texts: texts, id: "tMax", what: what,
        make: make, ray: ray(v(1, 1, 0), down), tMax: 3, expected: nil,
        otherwise: (
          .hitBeyondTMax,
          "the triangle is at t = 4, after tMax = 3: return nil unless "
            + "tMin < t < tMax"
        ),
        controls: ["inside"]),
    ]
  }
}
