import Geometry
import SceneDescription

/// Shapes of one's own (docs/ADDING-A-SHAPE.md): the probes do not know
/// their answers, and the fast engine asks the same code the course engine
/// does, so comparing the images cannot see their mistakes. What any
/// `Hittable` must do is checked instead, with rays aimed at its bounding
/// box: the hit's t in (tMin, tMax), its normal of unit length, its point
/// o + t·d inside the box, the same point found again by a second ray
/// started 3/4 of the way there along the same line, nothing before the
/// nearest hit, and nothing at or before a tMin set at that hit.
///
/// Tolerance: 10⁻⁶ of the box's size (plus the rounding of the point's
/// coordinates) for points, 10⁻⁶ for |n| − 1: a shape of one's own may
/// lose half of Double's digits and pass, while a t in other units (the
/// rays' directions have length 3) or a normal not normalised is off by
/// far more.
extension ShapeProbes {
  /// How many shapes of each type are checked, and with how many rays.
  static let ownChecked = 8
  static let ownRays = 48

  static func checkOwn(_ own: [Shape], into report: inout ShapeProbeReport) {
    var types: [String] = []
    var byType: [String: [Shape]] = [:]
    for shape in own {
      let name = String(describing: type(of: shape.object))
      if byType[name] == nil { types.append(name) }
      byType[name, default: []].append(shape)
    }
    for name in types {
      let shapes = byType[name] ?? []
      let checked = shapes.prefix(ownChecked)
      var rays = 0
      var hits = 0
      var failure: ShapeDiagnosis?
      for (ordinal, shape) in checked.enumerated() where failure == nil {
        let label =
          shapes.count == 1 ? name : "\(name) \(ordinal + 1) of \(shapes.count)"
        let outcome = check(shape.object, label: label, seed: ordinal)
        rays += outcome.rays
        hits += outcome.hits
        failure = outcome.failure
      }
      let which =
        checked.count == shapes.count
        ? (shapes.count == 1 ? "it" : "all \(shapes.count)")
        : "the first \(checked.count) of \(shapes.count)"
      var note =
        "\(name): a shape of one's own, which the probes do not know; "
        + "checked what any Hittable must do (t in (tMin, tMax), unit "
        + "normals, hits inside its bounding box, t along the ray) on "
        + "\(which) with \(rays) rays, \(hits) \(hits == 1 ? "hit" : "hits")"
      if hits == 0 { note += ": none hit, so nothing was checked" }
      report.notes.append(note)
      if let failure {
        report.notes.append("  " + failure.line)
        report.diagnoses.append(failure)
      }
    }
  }

  /// The rays of one shape: the count, the hits and the first failure.
  static func check(_ object: any Hittable, label: String, seed: Int)
    -> (rays: Int, hits: Int, failure: ShapeDiagnosis?)
  {
    var random = SplitMix64(seed: 0x0A11_5AFE + UInt64(seed))
    let box = object.boundingBox
    let center = box?.center ?? .zero
    let half = box.map { ($0.upper - $0.lower) * 0.5 } ?? Vector3(1, 1, 1)
    let reach = half.length > 0 ? half.length : 1
    func unit() -> Vector3<Double> {
      while true {
        let p = Vector3(
          Double.random(in: -1...1, using: &random),
          Double.random(in: -1...1, using: &random),
          Double.random(in: -1...1, using: &random))
        if (0.01...1).contains(p.lengthSquared) { return p.normalized() }
      }
    }
    var hits = 0
    for index in 0..<ownRays {
      let origin = center + unit() * (4 * reach)
      // Half the rays at points inside the box, half at points around it.
      let spread =
        index.isMultiple(of: 2) ? half : Vector3(reach, reach, reach) * 2
      let target =
        center
        + Vector3(
          Double.random(in: -1...1, using: &random) * spread.x,
          Double.random(in: -1...1, using: &random) * spread.y,
          Double.random(in: -1...1, using: &random) * spread.z)
      let ray = Ray(
        origin: origin, direction: (target - origin).normalized() * 3)
      guard let hit = object.intersect(ray, after: 0, before: .infinity)
      else { continue }
      hits += 1
      let slack = 1e-6 * reach + 1e-12 * ray.point(at: hit.t).maxMagnitude
      if let (cause, says) = judge(
        object, ray: ray, hit: hit, box: box, slack: slack)
      {
        let line =
          "\(label): the ray from \(ShapeProbe.text(ray.origin)) along "
          + "\(ShapeProbe.text(ray.direction)) hits at t = \(hit.t) with "
          + "normal \(ShapeProbe.text(hit.normal)): \(says)"
        return (
          index + 1, hits,
          ShapeDiagnosis(
            shape: label, probe: "ray \(index)", cause: cause, line: line,
            isOwnShape: true)
        )
      }
    }
    return (ownRays, hits, nil)
  }

  /// What is wrong with one hit, if anything.
  static func judge(
    _ object: any Hittable, ray: Ray<Double>, hit: Hit<Double>,
    box: BoundingBox?, slack: Double
  ) -> (ProbeCause, String)? {
    let within = "return nil unless tMin < t < tMax"
    guard hit.t > 0, hit.t < .infinity else {
      return (
        .ownOutsideInterval,
        "asked for a hit in (0, ∞), it gives t = \(hit.t): \(within)"
      )
    }
    let length = hit.normal.length
    guard abs(length - 1) <= 1e-6 else {
      return (
        .ownNormalNotUnit,
        "the normal has length \(Float(length)), not 1: normalise it"
      )
    }
    let point = ray.point(at: hit.t)
    if let box {
      let outside = (0..<3).contains {
        point[$0] < box.lower[$0] - slack || point[$0] > box.upper[$0] + slack
      }
      if outside {
        return (
          .ownHitOutsideBox,
          "its point o + t·d = \(ShapeProbe.text(point)) is outside its "
            + "bounding box, "
            + "\(ShapeProbe.text(box.lower)) to "
            + "\(ShapeProbe.text(box.upper)): the box must hold every point "
            + "it can be hit at, and t counts multiples of the direction "
            + "as given (here |d| = 3)"
        )
      }
    }
    let start = ray.point(at: hit.t * 0.75)
    let again = object.intersect(
      Ray(origin: start, direction: ray.direction), after: 0,
      before: .infinity)
    let found = again.map { (start + ray.direction * $0.t - point).length }
    if found.map({ $0 > slack }) ?? true {
      let said = again.map { "finds t = \($0.t)" } ?? "misses"
      return (
        .ownTAlongRay,
        "a second ray from \(ShapeProbe.text(start)), 3/4 of the way, "
          + "along the same "
          + "direction should find the same point at t = \(hit.t * 0.25), "
          + "and \(said): t counts multiples of the direction as given "
          + "(|d| = 3) from the ray's origin"
      )
    }
    if let nearer = object.intersect(
      ray, after: 0, before: hit.t * 0.5)
    {
      return (
        .ownOutsideInterval,
        "asked for a hit before tMax = \(hit.t * 0.5), it gives "
          + "t = \(nearer.t), though its nearest hit is at \(hit.t): "
          + within
      )
    }
    if let later = object.intersect(ray, after: hit.t, before: .infinity),
      !(later.t > hit.t)
    {
      return (
        .ownOutsideInterval,
        "asked for a hit after tMin = \(hit.t), it gives t = \(later.t): "
          + within
      )
    }
    return nil
  }
}
