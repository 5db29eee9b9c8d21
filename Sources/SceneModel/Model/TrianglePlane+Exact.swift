/// The plane of a triangle known beyond working precision, for the
/// triangles whose watertight t would lose digits: large beside their
/// distance from the eye, or thin.
///
/// The watertight test's t is Σ wᵢ·zᵢ / Σ wᵢ, the vertices' depths along
/// the ray weighted by edge functions computed from the sheared vertices.
/// Each sheared coordinate carries a rounding of the order of ε times the
/// vertex's distance, so each weight is off by ε·(distance)·(edge), while
/// Σ wᵢ is twice the projected area: t is off by about
///
///     ε · (longest edge² / twice the area) · max(1, longest edge / distance)
///
/// relative (times 1/cos of the angle of incidence, which the exact t's own
/// sensitivity to the ray's direction shares). The first factor is 1.15
/// for an equilateral triangle and 10⁴ for a sliver of aspect 10⁻⁴, the
/// second 10³ for a ground triangle 10³ times the eye's height across.
/// `needsExactT` estimates that product from the rounded vertices; a
/// triangle where it exceeds `conditionLimit` takes t from its plane:
///
///     t = k / (n·d),   n = (v1 − v0) × (v2 − v0),   k = n·(v0 − o)
///
/// with n and k found exactly from the scene's Double vertices and eye
/// (`ExactSum`), n scaled by a power of two to length in [½, 1) and kept as
/// a rounded normal plus the tail it could not hold, k rounded once. The
/// ray's n·d is plain where it cannot cancel and compensated, tail
/// included, where it can (`PlaneIntersection.stableT`), so t is within a
/// few ulps of the exact intersection of the computed ray with the
/// triangle as written, whatever its size or shape. The watertight test
/// still decides hit or miss and gives the barycentrics, so meshes stay
/// watertight.
extension TrianglePlane {
  /// The estimated error factor of the watertight t (in ε) above which a
  /// triangle's t is taken from its exact plane. Below it the watertight
  /// t is within a few ulps (measured in `TriangleAccuracyTests`), and
  /// the triangles of ordinary meshes (factor 1.2 to 3) never reach it.
  public static let conditionLimit = 16.0

  /// A triangle's plane seen from the eye, as the render reads it.
  public struct Exact<S: RayScalar>: Sendable {
    /// The normal, rounded to S, of length in [½, 1).
    public var normal: Vector3<S>
    /// The normal's digits beyond `normal`, rounded to S.
    public var normalTail: Vector3<S>
    /// n·(v0 − o), exact for n = normal + normalTail, rounded once.
    public var distance: S
    /// One non-zero component and no tail: n·d is then one rounded
    /// product.
    public var isAxisAligned: Bool

    @inlinable
    public init(
      normal: Vector3<S>, normalTail: Vector3<S>, distance: S,
      isAxisAligned: Bool
    ) {
      self.normal = normal
      self.normalTail = normalTail
      self.distance = distance
      self.isAxisAligned = isAxisAligned
    }

    /// The plane's t for a ray from o along d, in (tMin, tMax), or nil.
    @inlinable @inline(__always)
    public func t(direction d: Vector3<S>, after tMin: S, before tMax: S)
      -> S?
    {
      PlaneIntersection.stableT(
        normal: normal, normalTail: normalTail, distance: distance,
        isAxisAligned: isAxisAligned, direction: d, after: tMin,
        before: tMax)
    }
  }

  /// Whether the watertight t of the triangle with vertices `relative`
  /// (relative to the eye, as the records hold them) may be off by more
  /// than `conditionLimit` ε: the estimate above, from the rounded
  /// vertices, in Double. The distance is bounded below by the larger of
  /// the plane's distance and the gap between the eye and the triangle's
  /// box (in max-norm, never more than the true distance), so a triangle
  /// seen edge-on from afar is not taken for a large one.
  public static func needsExactT<S: RayScalar>(
    relative: (Vector3<S>, Vector3<S>, Vector3<S>)
  ) -> Bool {
    let a = Vector3<Double>(relative.0)
    let b = Vector3<Double>(relative.1)
    let c = Vector3<Double>(relative.2)
    let (e1, e2, e3) = (b - a, c - a, c - b)
    let cross = e1.cross(e2)
    let twiceArea = cross.length
    guard twiceArea > 0, twiceArea.isFinite else { return false }
    let longestSquared = Swift.max(
      e1.lengthSquared, e2.lengthSquared, e3.lengthSquared)
    let thinness = longestSquared / twiceArea
    let planeDistance = cross.dot(a).magnitude / twiceArea
    func gap(_ p: Double, _ q: Double, _ r: Double) -> Double {
      let (low, high) = (Swift.min(p, q, r), Swift.max(p, q, r))
      return low > 0 ? low : (high < 0 ? -high : 0)
    }
    let boxGap = Swift.max(
      gap(a.x, b.x, c.x), gap(a.y, b.y, c.y), gap(a.z, b.z, c.z))
    let near = Swift.max(planeDistance, boxGap)
    let reach = longestSquared.squareRoot() / near
    return thinness * Swift.max(1, reach) > conditionLimit
  }

  /// The exact plane of the triangle (v0, v1, v2) seen from `origin`
  /// (the scene's Double values, scaled by `LengthScale` when the scene
  /// is), in S; nil when the vertices are exactly collinear.
  public static func exact<S: RayScalar>(
    _ v0: Vector3<Double>, _ v1: Vector3<Double>, _ v2: Vector3<Double>,
    origin: Vector3<Double>, as _: S.Type = S.self
  ) -> Exact<S>? {
    func difference(_ p: Double, _ q: Double) -> [Double] {
      let d = Compensated.twoSum(p, -q)
      return d.error == 0 ? [d.sum] : [d.sum, d.error]
    }
    func differences(_ p: Vector3<Double>, _ q: Vector3<Double>)
      -> [[Double]]
    {
      [difference(p.x, q.x), difference(p.y, q.y), difference(p.z, q.z)]
    }
    let e1 = differences(v1, v0)
    let e2 = differences(v2, v0)
    // n_i = e1_j·e2_k − e1_k·e2_j, every partial product exact.
    func crossComponent(_ j: Int, _ k: Int) -> ExactSum {
      var sum = ExactSum()
      for p in e1[j] { for q in e2[k] { sum.add(p, times: q) } }
      for p in e1[k] { for q in e2[j] { sum.add(-p, times: q) } }
      return sum
    }
    var n = [crossComponent(1, 2), crossComponent(2, 0), crossComponent(0, 1)]
    guard n.contains(where: { !$0.isZero }) else { return nil }
    // A power of two bringing |n| into [½, 1): exact.
    let approximate = Vector3(n[0].estimate, n[1].estimate, n[2].estimate)
    let largest = approximate.maxMagnitude
    let unit = approximate * Double(
      sign: .plus, exponent: -largest.exponent, significand: 1)
    let exponent = -largest.exponent + (-unit.length.exponent - 1)
    n = n.map { $0.scaled(byPowerOfTwo: exponent) }
    var heads: [S] = []
    var tails: [S] = []
    var stored = [ExactSum](repeating: ExactSum(), count: 3)
    for axis in 0..<3 {
      let head: S = n[axis].rounded()
      var rest = n[axis]
      for part in head.exactDoubles { rest.add(-part) }
      let low: S = rest.rounded()
      heads.append(head)
      tails.append(low)
      for part in head.exactDoubles + low.exactDoubles {
        stored[axis].add(part)
      }
    }
    let normal = Vector3(heads[0], heads[1], heads[2])
    let tail = Vector3(tails[0], tails[1], tails[2])
    // k = (normal + tail)·(v0 − o), exact, rounded once.
    let offset = differences(v0, origin)
    var k = ExactSum()
    for axis in 0..<3 {
      for p in stored[axis].components {
        for q in offset[axis] { k.add(p, times: q) }
      }
    }
    return Exact(
      normal: normal, normalTail: tail, distance: k.rounded(),
      isAxisAligned: tail == .zero
        && PlaneIntersection.isAxisAligned(normal))
  }
}
