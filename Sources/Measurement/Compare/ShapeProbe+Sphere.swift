import Geometry

/// The sphere's probes and the transform's (over a sphere). Each ray's
/// answer is worked out beside it; f = o − center, a = d·d, b = 2 f·d,
/// c = f·f − r², the roots (−b ∓ √(b² − 4ac)) / 2a.
extension ShapeProbe {
  static func v(_ x: Double, _ y: Double, _ z: Double) -> Vector3<Double> {
    Vector3(x, y, z)
  }

  static func ray(_ origin: Vector3<Double>, _ direction: Vector3<Double>)
    -> Ray<Double>
  {
    Ray(origin: origin, direction: direction)
  }

  static var sphereTexts: ShapeTexts {
    ShapeTexts(
      name: "Sphere",
      normalLength: {
        "the normal has length \(text($0)) (the radius is 2), not 1: it is "
          + "(P − center) / radius (or normalise it)"
      },
      normalTurned: "the normal points into the sphere: it is "
        + "(P − center) / radius, outward, for a ray from inside too (do "
        + "not turn it towards the ray)",
      normalDirection: "the normal is (P − center) / radius at the hit "
        + "P = o + t·d")
  }

  /// Nine rays at spheres of radius 2 (so that |P − center| = 2 shows),
  /// one at the origin and one moved away from it.
  static var sphere: [ShapeProbe] {
    let texts = sphereTexts
    let moved = "the sphere of centre (1, 2, -10), radius 2"
    func ball(_ center: Vector3<Double>) -> (ShapeFactories) -> any Hittable {
      { $0.sphere(center, 2, 0) }
    }
    let atOrigin = ball(.zero)
    let away = ball(v(1, 2, -10))
    func farRoot(_ t: Double) -> Mistake {
      Mistake(
        answer: .hit(t: t), cause: .farRoot,
        says: "t = \(text(t)) is the far root: return the near one, "
          + "(−b − √(b² − 4ac)) / 2a, and the far one only when the near "
          + "one is not after tMin")
    }
    return [
      // f = (0, 0, 10): b = −20, c = 96, Δ = 16, roots 8 and 12.
      ShapeProbe(
        texts: texts, id: "origin", what: "a sphere at the origin, radius 2",
        make: atOrigin, ray: ray(v(0, 0, 10), v(0, 0, -1)),
        expected: Expected(t: 8, normal: v(0, 0, 1)),
        mistakes: [farRoot(12)],
        otherwise: (
          .formula,
          "check the quadratic: a = d·d, b = 2 f·d, c = f·f − r² with "
            + "f = o − center, t = (−b − √(b² − 4ac)) / 2a"
        )),
      // The same ray and sphere, both moved by (1, 2, −10): the same
      // answer. With the centre not subtracted (f = o), a miss.
      ShapeProbe(
        texts: texts, id: "moved", what: "\(moved), away from the origin",
        make: away, ray: ray(v(1, 2, 0), v(0, 0, -1)),
        expected: Expected(t: 8, normal: v(0, 0, 1)),
        mistakes: [farRoot(12)],
        otherwise: (
          .centreNotSubtracted,
          "the centre is not subtracted (the same ray at the same sphere "
            + "at the origin hits): write f = o − center and use f, not o, "
            + "in b and c"
        ),
        controls: ["origin"]),
      // 2 from the centre, the radius: Δ = 0, the double root 10.
      ShapeProbe(
        texts: texts, id: "tangent", what: "\(moved), touched",
        make: away, ray: ray(v(3, 2, 0), v(0, 0, -1)),
        expected: Expected(t: 10, normal: v(1, 0, 0)),
        otherwise: (
          .tangentMissed,
          "the discriminant's test: this ray touches the sphere "
            + "(b² − 4ac = 0 exactly) and hits at its double root; test "
            + "b² − 4ac ≥ 0, not > 0"
        ),
        controls: ["moved"]),
      // 5 from the centre: Δ < 0.
      ShapeProbe(
        texts: texts, id: "miss", what: "\(moved), passed by",
        make: away, ray: ray(v(1, 7, 0), v(0, 0, -1)), expected: nil,
        mistakes: [
          Mistake(
            answer: .anyHit, cause: .discriminantTest,
            says: "the discriminant's test: this ray passes 5 from the "
              + "centre, farther than the radius, so b² − 4ac < 0 and "
              + "there is no root; return nil then")
        ],
        otherwise: (.discriminantTest, ""), controls: ["moved"]),
      // Away from the sphere: roots −12 and −8.
      ShapeProbe(
        texts: texts, id: "behind", what: "\(moved), behind the ray",
        make: away, ray: ray(v(1, 2, 0), v(0, 0, 1)), expected: nil,
        mistakes: [
          Mistake(
            answer: .anyHit, cause: .hitBehind,
            says: "hits behind the eye: both roots (−12 and −8) are "
              + "negative; return nil when neither root is in "
              + "(tMin, tMax)")
        ],
        otherwise: (.hitBehind, ""), controls: ["moved"]),
      // From inside, 1 from the centre: roots −1 and 3; at (1, 2, −12)
      // the outward normal is (0, 0, −1).
      ShapeProbe(
        texts: texts, id: "inside", what: "\(moved), from inside",
        make: away, ray: ray(v(1, 2, -9), v(0, 0, -1)),
        expected: Expected(t: 3, normal: v(0, 0, -1)),
        mistakes: [
          Mistake(
            answer: .hit(t: -1), cause: .insideMissed,
            says: "t = −1 is the near root, behind the ray's start: from "
              + "inside, return the far root, (−b + √(b² − 4ac)) / 2a")
        ],
        otherwise: (
          .insideMissed,
          "a ray from inside hits the far side: the near root (−1) is "
            + "behind its start, so return the far root, "
            + "(−b + √(b² − 4ac)) / 2a, when it is in (tMin, tMax)"
        ),
        controls: ["moved"]),
      // d = (0, 0, −2): a = 4, b = −40, c = 96, Δ = 64, roots 4 and 6;
      // the point 8 away is t = 4.
      ShapeProbe(
        texts: texts, id: "long",
        what: "\(moved), along a direction of "
          + "length 2",
        make: away, ray: ray(v(1, 2, 0), v(0, 0, -2)),
        expected: Expected(t: 4, normal: v(0, 0, 1)),
        mistakes: [
          farRoot(6),
          Mistake(
            answer: .hit(t: 8), cause: .directionNormalised,
            says: "t = 8 is the distance: the direction was normalised, "
              + "but t counts multiples of d as given (|d| = 2); do not "
              + "normalise it, and use a = d·d"),
        ],
        otherwise: (
          .directionLength,
          "t is not measured along the given direction (|d| = 2): a = d·d, "
            + "not 1, and t = (−b − √(b² − 4ac)) / 2a"
        ),
        controls: ["moved"]),
      ShapeProbe(
        texts: texts, id: "tMax", what: "a sphere at the origin, radius 2",
        make: atOrigin, ray: ray(v(0, 0, 10), v(0, 0, -1)), tMax: 6,
        expected: nil,
        otherwise: (
          .hitBeyondTMax,
          "this ray meets the sphere at t = 8 and 12, none before "
            + "tMax = 6: return nil unless tMin < t < tMax"
        ),
        controls: ["origin"]),
      // The near root 8 is not after tMin = 10: the far one, 12, at
      // (0, 0, −2).
      ShapeProbe(
        texts: texts, id: "tMin", what: "a sphere at the origin, radius 2",
        make: atOrigin, ray: ray(v(0, 0, 10), v(0, 0, -1)), tMin: 10,
        expected: Expected(t: 12, normal: v(0, 0, -1)),
        mistakes: [
          Mistake(
            answer: .hit(t: 8), cause: .farRootAfterTMin,
            says: "t = 8 is not after tMin = 10: the hit is then the far "
              + "root, 12; compare the roots with tMin, not with 0")
        ],
        otherwise: (
          .farRootAfterTMin,
          "the near root (8) is not after tMin = 10, so the hit is the "
            + "far root (12): compare the roots with tMin, not with 0"
        ),
        controls: ["origin"]),
    ]
  }

  static var transformTexts: ShapeTexts {
    ShapeTexts(
      name: "Transform",
      normalLength: {
        "the normal has length \(text($0)), not 1: normalise it after "
          + "(M⁻¹)ᵀ"
      },
      normalTurned: "the normal is turned: bring the object's normal back "
        + "by (M⁻¹)ᵀ, which keeps it outward",
      normalDirection: "bring the object's normal back by the inverse "
        + "transpose, (M⁻¹)ᵀ·n, then normalise it")
  }

  /// Four rays at a unit sphere at the origin, made by the sphere
  /// factory, placed by a transform: its ray in object space is
  /// M⁻¹·(o, 1) and M⁻¹·(d, 0), not normalised, so t is the same in both
  /// spaces.
  static var transform: [ShapeProbe] {
    let texts = transformTexts
    func placed(_ matrix: Matrix4<Double>) -> (ShapeFactories)
      -> (any Hittable)?
    {
      { $0.transform(matrix, $0.sphere(.zero, 1, 0)) }
    }
    let translated = Matrix4<Double>.translation(v(1, 2, -10))
    let scaled = translated * .uniformScale(2)
    // M = T(0, 0, −10)·R·S: S = scale(2, 1, 1), R turns (x, y, z) into
    // (−y, x, z). The object's point p = (0.48, 0.64, 0.6) (|p| = 1, the
    // normal there) is drawn at M·p = (−0.64, 0.96, −9.4). (M⁻¹)ᵀ = R·S⁻¹
    // takes p to (−0.64, 0.24, 0.6); M to (−0.64, 0.96, 0.6); M⁻¹ =
    // S⁻¹·Rᵀ to (0.32, −0.48, 0.6).
    let stretched = Matrix4<Double>(rows: [
      0, -1, 0, 0,
      2, 0, 0, 0,
      0, 0, 1, -10,
      0, 0, 0, 1,
    ])
    let p = v(0.48, 0.64, 0.6)
    let whatScaled = "a unit sphere scaled by 2, moved to (1, 2, -10)"
    return [
      // Object space: the ray from (0, 0, 10) along (0, 0, −1): t = 9.
      ShapeProbe(
        texts: texts, id: "translated",
        what: "a unit sphere moved to (1, 2, -10)",
        make: placed(translated), ray: ray(v(1, 2, 0), v(0, 0, -1)),
        expected: Expected(t: 9, normal: v(0, 0, 1)),
        otherwise: (
          .objectOrigin,
          "the ray's origin in object space is M⁻¹·(o, 1), a point: "
            + "inverse.transformPoint(o), the translation applied; the "
            + "direction M⁻¹·(d, 0), inverse.transformDirection(d)"
        )),
      // Object space: from (0, 0, 5) along (0, 0, −0.5): t = 8; along
      // the direction normalised, 4.
      ShapeProbe(
        texts: texts, id: "scaled", what: whatScaled,
        make: placed(scaled), ray: ray(v(1, 2, 0), v(0, 0, -1)),
        expected: Expected(t: 8, normal: v(0, 0, 1)),
        mistakes: [
          Mistake(
            answer: .hit(t: 4), cause: .objectDirectionNormalised,
            says: "t = 4 is measured in object space: leave the direction "
              + "M⁻¹·d unnormalised, so that t names the same point in "
              + "both spaces")
        ],
        otherwise: (
          .objectDirectionNormalised,
          "t must name the same point in world and object space: the "
            + "direction M⁻¹·(d, 0), not normalised, and t as the object "
            + "gives it"
        ),
        controls: ["translated"]),
      ShapeProbe(
        texts: texts, id: "stretched",
        what: "a unit sphere scaled by (2, 1, 1), turned 90° about z, "
          + "moved to (0, 0, -10)",
        make: placed(stretched), ray: ray(v(-0.64, 0.96, 0), v(0, 0, -1)),
        expected: Expected(t: 9.4, normal: v(-0.64, 0.24, 0.6).normalized()),
        mistakes: [
          Mistake(
            answer: .normal(v(-0.64, 0.96, 0.6)), cause: .normalByMatrix,
            says: "the normal is moved by M: normals go back by the "
              + "inverse transpose, inverse.transposed()"
              + ".transformDirection(n), then normalised"),
          Mistake(
            answer: .normal(v(0.32, -0.48, 0.6)), cause: .normalByInverse,
            says: "the normal is moved by M⁻¹: transpose it, "
              + "inverse.transposed().transformDirection(n)"),
          Mistake(
            answer: .normal(p), cause: .normalInObjectSpace,
            says: "the normal is the object's, left in object space: "
              + "bring it back by (M⁻¹)ᵀ, "
              + "inverse.transposed().transformDirection(n)"),
        ],
        otherwise: (
          .formula,
          "take the ray into object space by M⁻¹ (the origin as a point, "
            + "the direction as a direction) and keep the object's t"
        ),
        controls: ["scaled"]),
      // Object space: from (0, 0, 5) along (0, 0, −1): t = 4.
      ShapeProbe(
        texts: texts, id: "long",
        what: "\(whatScaled), along a direction "
          + "of length 2",
        make: placed(scaled), ray: ray(v(1, 2, 0), v(0, 0, -2)),
        expected: Expected(t: 4, normal: v(0, 0, 1)),
        mistakes: [
          Mistake(
            answer: .hit(t: 8), cause: .directionNormalised,
            says: "t = 8 is along the world direction normalised: t "
              + "counts multiples of d as given (|d| = 2); do not "
              + "normalise it")
        ],
        otherwise: (
          .directionLength,
          "t is not measured along the given direction (|d| = 2): take "
            + "d into object space as it is, M⁻¹·(d, 0)"
        ),
        controls: ["scaled"]),
    ]
  }
}
