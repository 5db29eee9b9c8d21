import Course
import Geometry

/// How the probes make each of the course's shapes: the course's own by
/// default (`course`); a test hands in deliberately broken ones.
package struct ShapeFactories {
  /// A sphere of `center` and `radius`, material `material`.
  package var sphere: (Vector3<Double>, Double, Int) -> any Hittable
  /// The plane n·P = `offset` of unit normal n, material `material`.
  package var plane: (Vector3<Double>, Double, Int) -> any Hittable
  package var triangle: (ProbedTriangle) -> any Hittable
  /// `object` placed by the matrix; nil when it has no inverse.
  package var transform: (Matrix4<Double>, any Hittable) -> (any Hittable)?

  package init(
    sphere: @escaping (Vector3<Double>, Double, Int) -> any Hittable,
    plane: @escaping (Vector3<Double>, Double, Int) -> any Hittable,
    triangle: @escaping (ProbedTriangle) -> any Hittable,
    transform: @escaping (Matrix4<Double>, any Hittable) -> (any Hittable)?
  ) {
    self.sphere = sphere
    self.plane = plane
    self.triangle = triangle
    self.transform = transform
  }

  /// The course's shapes (`Sources/Course`): what `--check` asks.
  package static var course: ShapeFactories {
    ShapeFactories(
      sphere: { Sphere(center: $0, radius: $1, materialIndex: $2) },
      plane: { Plane(normal: $0, offset: $1, materialIndex: $2) },
      triangle: { corners in
        var triangle = Triangle(
          corners.a, corners.b, corners.c,
          materialIndex: corners.materialIndex)
        triangle.normals = corners.normals
        triangle.textureCoordinates = corners.textureCoordinates
        return triangle
      },
      transform: { Transform(matrix: $0, object: $1) })
  }
}

/// A triangle as the probes give it: corners, and normals and texture
/// coordinates at the corners where a mesh would give them.
package struct ProbedTriangle {
  package var a, b, c: Vector3<Double>
  package var normals: (Vector3<Double>, Vector3<Double>, Vector3<Double>)?
  package var textureCoordinates:
    (
      TextureCoordinate<Double>, TextureCoordinate<Double>,
      TextureCoordinate<Double>
    )?
  package var materialIndex = 0
}

/// The causes the probes name: one per common mistake.
package enum ProbeCause: String, Sendable {
  // Any shape.
  case formula, hitBehind, hitBeyondTMax, directionNormalised
  case directionLength, normalNotUnit, normalTurned, normalDirection
  // The sphere.
  case centreNotSubtracted, farRoot, discriminantTest, tangentMissed
  case insideMissed, farRootAfterTMin
  // The plane.
  case offsetSign, backSideMissed, parallelHit
  // The triangle.
  case edgeBeta, edgeGamma, edgeSum, normalsNotInterpolated
  case textureNotInterpolated
  // The transform.
  case objectOrigin, objectDirectionNormalised, normalByMatrix
  case normalByInverse, normalInObjectSpace
  // A shape of one's own.
  case ownOutsideInterval, ownNormalNotUnit, ownHitOutsideBox, ownTAlongRay
}

/// One failing probe: the shape, which probe, the cause and the line that
/// says it all.
package struct ShapeDiagnosis: Sendable {
  package var shape: String
  package var probe: String
  package var cause: ProbeCause
  package var line: String
  /// A shape of one's own, checked as any `Hittable`.
  package var isOwnShape = false
}

/// What a shape's messages say where every probe of it says the same.
struct ShapeTexts {
  var name: String
  /// What to write when the normal has the right direction and length
  /// `$0`.
  var normalLength: (Double) -> String
  /// When the normal is the expected one turned around.
  var normalTurned: String
  /// When the normal points elsewhere.
  var normalDirection: String
}

/// A ray whose answer is known in closed form, asked of one shape made by
/// the factories, with the answers the common mistakes give.
///
/// Tolerance: every expected t, normal and texture coordinate is exact in
/// Double or (the rotated transform, the interpolated normal) the nearest
/// Double to a closed form; a correct intersection in Double, by any
/// formula, lands within a few ulps of it (10⁻¹⁵ relative), while every
/// mistake named here is off by more than 10⁻². 10⁻⁹ relative (absolute
/// for the unit vectors and coordinates) lies far from both.
struct ShapeProbe {
  static let tolerance = 1e-9

  /// What the mistake gives on this probe's ray.
  enum Answer {
    case miss
    case anyHit
    /// A hit at t ≤ tMin.
    case hitBefore
    case hit(t: Double)
    /// A hit at the expected t whose normal has this direction.
    case normal(Vector3<Double>)
    /// A hit at the expected t without a texture coordinate.
    case noTexture
  }

  struct Mistake {
    var answer: Answer
    var cause: ProbeCause
    var says: String
  }

  struct Expected {
    var t: Double
    var normal: Vector3<Double>
    var texture: TextureCoordinate<Double>? = nil
  }

  var texts: ShapeTexts
  /// A short name, which controls name.
  var id: String
  /// What the probe asks, as its line begins: "a sphere away from the
  /// origin (centre (1, 2, -10), radius 2)".
  var what: String
  var make: (ShapeFactories) -> (any Hittable)?
  var ray: Ray<Double>
  var tMin = 0.0
  var tMax = Double.infinity
  /// Nil: the ray must miss.
  var expected: Expected?
  var mistakes: [Mistake] = []
  /// The cause when no mistake's answer matches (never, for a probe that
  /// must miss and names any hit a mistake).
  var otherwise: (cause: ProbeCause, says: String)
  /// Probes that ask the same without what this one adds: when one of
  /// them fails, its cause is this one's too, and this one says nothing.
  var controls: [String] = []

  /// The shape's answer: nil when it passes, else the cause and the line.
  func judge(_ got: Hit<Double>?) -> ShapeDiagnosis? {
    if passes(got) { return nil }
    let (cause, says) = diagnose(got)
    let line =
      "\(texts.name), \(what): the ray from \(Self.text(ray.origin)) along "
      + "\(Self.text(ray.direction))\(interval) should \(expectation), and "
      + "\(Self.text(got, against: expected)): \(says)"
    return ShapeDiagnosis(
      shape: texts.name, probe: id, cause: cause, line: line)
  }

  func passes(_ got: Hit<Double>?) -> Bool {
    guard let expected else { return got == nil }
    guard let got, Self.close(got.t, expected.t),
      Self.close(got.normal, expected.normal)
    else { return false }
    guard let texture = expected.texture else { return true }
    guard let found = got.textureCoordinate else { return false }
    return Self.close(
      Vector3(found.u, found.v, 0), Vector3(texture.u, texture.v, 0))
  }

  /// The first mistake whose answer matches, else what any shape gets
  /// wrong (a t outside the interval, the normal's length or direction),
  /// else the probe's own cause.
  func diagnose(_ got: Hit<Double>?) -> (ProbeCause, String) {
    for mistake in mistakes where matches(mistake.answer, got) {
      return (mistake.cause, mistake.says)
    }
    if let got, got.t <= tMin {
      return (
        .hitBehind,
        "t = \(Self.text(got.t)) is not after tMin = \(Self.text(tMin)) "
          + "(a hit behind the ray's start, where tMin = 0): return nil "
          + "unless tMin < t < tMax"
      )
    }
    if let got, got.t >= tMax {
      return (
        .hitBeyondTMax,
        "t = \(Self.text(got.t)) is not before tMax = \(Self.text(tMax)): "
          + "return nil unless tMin < t < tMax"
      )
    }
    guard let expected, let got, Self.close(got.t, expected.t) else {
      return otherwise
    }
    let n = got.normal
    if !Self.close(n, expected.normal) {
      if Self.parallel(n, expected.normal), !Self.close(n.length, 1) {
        return (.normalNotUnit, texts.normalLength(n.length))
      }
      if Self.parallel(n, -expected.normal) {
        return (.normalTurned, texts.normalTurned)
      }
      return (.normalDirection, texts.normalDirection)
    }
    return (
      .textureNotInterpolated,
      "the texture coordinate is (1 − β − γ)·t0 + β·t1 + γ·t2, the "
        + "corners' coordinates weighted as the normals are"
    )
  }

  func matches(_ answer: Answer, _ got: Hit<Double>?) -> Bool {
    switch answer {
    case .miss: return got == nil
    case .anyHit: return got != nil
    case .hitBefore: return got.map { $0.t <= tMin } ?? false
    case .hit(let t): return got.map { Self.close($0.t, t) } ?? false
    case .normal(let direction):
      guard let got, let expected, Self.close(got.t, expected.t) else {
        return false
      }
      return Self.parallel(got.normal, direction)
    case .noTexture:
      guard let got, let expected, Self.close(got.t, expected.t) else {
        return false
      }
      return got.textureCoordinate == nil
    }
  }

  var interval: String {
    switch (tMin, tMax) {
    case (0, .infinity): ""
    case (0, _): " (tMax = \(Self.text(tMax)))"
    case (_, .infinity): " (tMin = \(Self.text(tMin)))"
    default: " (tMin = \(Self.text(tMin)), tMax = \(Self.text(tMax)))"
    }
  }

  var expectation: String {
    guard let expected else { return "miss" }
    var text =
      "hit at t = \(Self.text(expected.t)) with normal "
      + Self.text(expected.normal)
    if let texture = expected.texture {
      text += " and texture coordinate \(Self.text(texture))"
    }
    return text
  }
}

extension ShapeProbe {
  static func close(_ a: Double, _ b: Double) -> Bool {
    abs(a - b) <= tolerance * max(abs(b), 1)
  }

  static func close(_ a: Vector3<Double>, _ b: Vector3<Double>) -> Bool {
    (a - b).maxMagnitude <= tolerance
  }

  /// Whether two vectors point the same way, whatever their lengths.
  static func parallel(_ a: Vector3<Double>, _ b: Vector3<Double>) -> Bool {
    a.dot(b) >= (1 - tolerance) * a.length * b.length && a.length > 0
  }

  /// A number as it reads best: whole numbers without ".0".
  static func text(_ x: Double) -> String {
    if x.isNaN { return "NaN" }  // not "-nan", as Swift prints some
    if x == x.rounded(), abs(x) < 1e15 { return "\(Int(x))" }
    return "\(x)"
  }

  /// A vector, each component to a float's digits (whole ones without
  /// ".0"): the probes' vectors differ in the second digit or sooner.
  static func text(_ v: Vector3<Double>) -> String {
    func part(_ x: Double) -> String {
      if x.isNaN { return "NaN" }
      return x == x.rounded() && abs(x) < 1e15 ? "\(Int(x))" : "\(Float(x))"
    }
    return "(\(part(v.x)), \(part(v.y)), \(part(v.z)))"
  }

  static func text(_ uv: TextureCoordinate<Double>) -> String {
    "(\(text(uv.u)), \(text(uv.v)))"
  }

  /// What came back, in the terms of the expectation.
  static func text(_ got: Hit<Double>?, against expected: Expected?)
    -> String
  {
    guard let got else { return "misses" }
    var text = "hits at t = \(self.text(got.t)) with normal "
    if let expected, !close(got.normal, expected.normal),
      self.text(got.normal) == self.text(expected.normal)
    {
      text += "\(got.normal)"  // differs beyond a float's digits
    } else {
      text += self.text(got.normal)
    }
    if expected?.texture != nil {
      text +=
        got.textureCoordinate.map {
          " and texture coordinate \(self.text($0))"
        } ?? " and no texture coordinate"
    }
    return text
  }
}
