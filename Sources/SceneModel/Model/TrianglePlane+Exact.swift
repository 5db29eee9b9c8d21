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
  /// vertices, in Double and in squares (no square root: it runs for every
  /// triangle of every mesh), after a power of two brings the largest
  /// coordinate near 1 (exact, and every square then in range). The
  /// distance is bounded below by the larger of the plane's distance and
  /// the gap between the eye and the triangle's box (in max-norm, never
  /// more than the true distance), so a triangle seen edge-on from afar is
  /// not taken for a large one.
  public static func needsExactT<S: RayScalar>(
    relative: (Vector3<S>, Vector3<S>, Vector3<S>)
  ) -> Bool {
    let largest = Double(
      Swift.max(
        relative.0.maxMagnitude, relative.1.maxMagnitude,
        relative.2.maxMagnitude))
    guard largest > 0, largest.isFinite else { return false }
    let scale = Double(sign: .plus, exponent: -largest.exponent, significand: 1)
    let a = Vector3<Double>(relative.0) * scale
    let b = Vector3<Double>(relative.1) * scale
    let c = Vector3<Double>(relative.2) * scale
    let (e1, e2, e3) = (b - a, c - a, c - b)
    let cross = e1.cross(e2)
    let crossSquared = cross.lengthSquared
    guard crossSquared > 0 else { return false }
    let longestSquared = Swift.max(
      e1.lengthSquared, e2.lengthSquared, e3.lengthSquared)
    let k = cross.dot(a)
    let planeDistanceSquared = k * k / crossSquared
    func gap(_ p: Double, _ q: Double, _ r: Double) -> Double {
      let (low, high) = (Swift.min(p, q, r), Swift.max(p, q, r))
      return low > 0 ? low : (high < 0 ? -high : 0)
    }
    let boxGap = Swift.max(
      gap(a.x, b.x, c.x), gap(a.y, b.y, c.y), gap(a.z, b.z, c.z))
    let nearSquared = Swift.max(planeDistanceSquared, boxGap * boxGap)
    // (longest² / twice the area)² · max(1, longest² / near²) > limit².
    let thinnessSquared = longestSquared * longestSquared / crossSquared
    let reachSquared = longestSquared / nearSquared
    return thinnessSquared * Swift.max(1, reachSquared)
      > conditionLimit * conditionLimit
  }

  /// The exact plane of the triangle (v0, v1, v2) seen from `origin`
  /// (the scene's Double values, scaled by `LengthScale` when the scene
  /// is), in S; nil when the vertices are exactly collinear.
  ///
  /// n is exact (`ExactSum` over the products of the edges' exact
  /// differences), then rounded to Double's twice precision and scaled; k
  /// is summed from the exact products of the stored normal and the exact
  /// differences v0 − o as if in twice Double's precision (Sum2, as the
  /// camera-relative constants of spheres are) and rounded once.
  public static func exact<S: RayScalar>(
    _ v0: Vector3<Double>, _ v1: Vector3<Double>, _ v2: Vector3<Double>,
    origin: Vector3<Double>, as _: S.Type = S.self
  ) -> Exact<S>? {
    typealias Pair = (sum: Double, error: Double)
    func differences(_ p: Vector3<Double>, _ q: Vector3<Double>)
      -> (Pair, Pair, Pair)
    {
      (
        Compensated.twoSum(p.x, -q.x), Compensated.twoSum(p.y, -q.y),
        Compensated.twoSum(p.z, -q.z)
      )
    }
    let e1 = differences(v1, v0)
    let e2 = differences(v2, v0)
    // p·q − r·s for exact pairs, every partial product exact.
    func crossComponent(_ p: Pair, _ q: Pair, _ r: Pair, _ s: Pair)
      -> ExactSum
    {
      var sum = ExactSum()
      for (x, y) in [
        (p.sum, q.sum), (p.sum, q.error), (p.error, q.sum),
        (p.error, q.error), (-r.sum, s.sum), (-r.sum, s.error),
        (-r.error, s.sum), (-r.error, s.error),
      ] where x != 0 && y != 0 {
        sum.add(x, times: y)
      }
      return sum
    }
    let exactNormal = [
      crossComponent(e1.1, e2.2, e1.2, e2.1),
      crossComponent(e1.2, e2.0, e1.0, e2.2),
      crossComponent(e1.0, e2.1, e1.1, e2.0),
    ]
    guard exactNormal.contains(where: { !$0.isZero }) else { return nil }
    var n = exactNormal.map(\.pair)
    // A power of two bringing |n| into [½, 1): exact.
    let largest = Swift.max(n[0].hi.magnitude, n[1].hi.magnitude, n[2].hi.magnitude)
    let unit = Vector3(n[0].hi, n[1].hi, n[2].hi)
      * Double(sign: .plus, exponent: -largest.exponent, significand: 1)
    let exponent = -largest.exponent - unit.length.exponent - 1
    n = n.map {
      (
        Double(sign: .plus, exponent: exponent, significand: $0.hi),
        Double(sign: .plus, exponent: exponent, significand: $0.lo)
      )
    }
    // The normal rounded to S and its tail, and the Doubles whose sum is
    // exactly the stored normal + tail.
    var heads: [S] = []
    var tails: [S] = []
    var parts: [[Double]] = []
    for (hi, lo) in n {
      let head: S = CameraRelative.narrowed(hi, lo)
      let tail: S
      if S.significandBitCount <= Double.significandBitCount {
        tail = S((hi - Double(head)) + lo)
        parts.append([Double(head), Double(tail)])
      } else {
        tail = (S(hi) - head) + S(lo)
        parts.append(head.exactDoubles + tail.exactDoubles)
      }
      heads.append(head)
      tails.append(tail)
    }
    let normal = Vector3(heads[0], heads[1], heads[2])
    let tail = Vector3(tails[0], tails[1], tails[2])
    let offset = differences(v0, origin)
    let offsets = [offset.0, offset.1, offset.2]
    let distance: S = withUnsafeTemporaryAllocation(
      of: Double.self, capacity: 64
    ) { terms in
      var count = 0
      for axis in 0..<3 {
        for part in parts[axis] {
          for d in [offsets[axis].sum, offsets[axis].error] where d != 0 {
            let product = Compensated.twoProduct(part, d)
            terms[count] = product.product
            terms[count + 1] = product.error
            count += 2
          }
        }
      }
      return CameraRelative.roundedSum(
        UnsafeMutableBufferPointer(rebasing: terms[0..<count]))
    }
    return Exact(
      normal: normal, normalTail: tail, distance: distance,
      isAxisAligned: tail == .zero
        && PlaneIntersection.isAxisAligned(normal))
  }
}
