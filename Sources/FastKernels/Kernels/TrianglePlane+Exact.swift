import ExactArithmetic
import Geometry
import SceneDescription
import PlatformSupport

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
  @usableFromInline
  package static let conditionLimit = 16.0

  /// A triangle's plane seen from the eye, as the render reads it.
  @usableFromInline
  package struct Exact<S: RayScalar>: Sendable {
    /// The normal, rounded to S, of length in [½, 1).
    @usableFromInline
    package var normal: Vector3<S>
    /// The normal's digits beyond `normal`, rounded to S.
    @usableFromInline
    package var normalTail: Vector3<S>
    /// n·(v0 − o), exact for n = normal + normalTail, rounded once.
    @usableFromInline
    package var distance: S
    /// One non-zero component and no tail: n·d is then one rounded
    /// product.
    @usableFromInline
    package var isAxisAligned: Bool

    @inlinable
    package init(
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
    package func t(direction d: Vector3<S>, after tMin: S, before tMax: S)
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
  /// vertices, in their own precision and in squares (no square root,
  /// conversion or scaling: it runs for every triangle of every mesh).
  /// Each quotient is formed so that its intermediates stay within the
  /// lengths' squares: in range for a compiled scene, whose lengths
  /// `LengthScale` keeps within 2^±(E/4) of 1; a square that underflows to
  /// zero (a sliver near that window's small end) asks for the exact
  /// plane, which settles it. The distance is bounded below by the larger
  /// of the plane's distance and the gap between the eye and the
  /// triangle's box (in max-norm, never more than the true distance), so a
  /// triangle seen edge-on from afar is not taken for a large one.
  @inlinable
  package static func needsExactT<S: RayScalar>(
    relative: (Vector3<S>, Vector3<S>, Vector3<S>)
  ) -> Bool {
    let (a, b, c) = relative
    let (e1, e2, e3) = (b - a, c - a, c - b)
    let cross = e1.cross(e2)
    let crossSquared = cross.lengthSquared
    guard crossSquared > 0 else { return crossSquared == 0 }
    // Two-argument minima and maxima throughout: the variadic ones cost
    // more than the rest of the estimate.
    let longestSquared = Swift.max(
      Swift.max(e1.lengthSquared, e2.lengthSquared), e3.lengthSquared)
    let k = cross.dot(a)
    let planeDistanceSquared = (k / crossSquared) * k
    @inline(__always) func gap(_ p: S, _ q: S, _ r: S) -> S {
      let low = Swift.min(Swift.min(p, q), r)
      let high = Swift.max(Swift.max(p, q), r)
      return low > 0 ? low : (high < 0 ? -high : 0)
    }
    let boxGap = Swift.max(
      Swift.max(gap(a.x, b.x, c.x), gap(a.y, b.y, c.y)), gap(a.z, b.z, c.z))
    let nearSquared = Swift.max(planeDistanceSquared, boxGap * boxGap)
    // (longest² / twice the area)² · max(1, longest² / near²) > limit².
    let thinnessSquared = (longestSquared / crossSquared) * longestSquared
    let reachSquared = longestSquared / nearSquared
    return thinnessSquared * Swift.max(1, reachSquared)
      > S(conditionLimit * conditionLimit)
  }

  /// The exact plane of the triangle (v0, v1, v2) seen from `origin`
  /// (the scene's Double values, scaled by `LengthScale` when the scene
  /// is), in S; nil when the vertices are exactly collinear.
  ///
  /// n is exact (`ExactSum` over the products of the edges' exact
  /// differences), then rounded to twice Double's precision and scaled; k
  /// is summed from the exact products of the stored normal and the exact
  /// differences v0 − o as if in twice Double's precision (Sum2, as the
  /// camera-relative constants of spheres are) and rounded once.
  @usableFromInline
  package static func exact<S: RayScalar>(
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
    var scratch = ExactSum()
    func crossComponent(_ p: Pair, _ q: Pair, _ r: Pair, _ s: Pair)
      -> (hi: Double, lo: Double)
    {
      scratch.removeAll()
      scratch.add(p.sum, times: q.sum)
      scratch.add(p.sum, times: q.error)
      scratch.add(p.error, times: q.sum)
      scratch.add(p.error, times: q.error)
      scratch.add(-r.sum, times: s.sum)
      scratch.add(-r.sum, times: s.error)
      scratch.add(-r.error, times: s.sum)
      scratch.add(-r.error, times: s.error)
      return scratch.pair
    }
    var n = (
      crossComponent(e1.1, e2.2, e1.2, e2.1),
      crossComponent(e1.2, e2.0, e1.0, e2.2),
      crossComponent(e1.0, e2.1, e1.1, e2.0)
    )
    let largest = Swift.max(
      n.0.hi.magnitude, n.1.hi.magnitude, n.2.hi.magnitude)
    guard largest > 0 else { return nil }
    // A power of two bringing |n| into [½, 1): exact.
    let unit =
      Vector3(n.0.hi, n.1.hi, n.2.hi)
      * Double(sign: .plus, exponent: -largest.exponent, significand: 1)
    let exponent = -largest.exponent - unit.length.exponent - 1
    func scaled(_ p: (hi: Double, lo: Double)) -> (hi: Double, lo: Double) {
      (
        Double(sign: .plus, exponent: exponent, significand: p.hi),
        Double(sign: .plus, exponent: exponent, significand: p.lo)
      )
    }
    n = (scaled(n.0), scaled(n.1), scaled(n.2))
    // The normal rounded to S, its tail, and Doubles whose sum is exactly
    // the stored normal + tail (two for S no wider than Double).
    func stored(_ p: (hi: Double, lo: Double)) -> (
      head: S, tail: S, parts: [Double]
    ) {
      if S.self == Double.self { return (S(p.hi), S(p.lo), []) }
      if S.significandBitCount < Double.significandBitCount {
        let head: S = CameraRelative.narrowed(p.hi, p.lo)
        return (head, S((p.hi - Double(head)) + p.lo), [])
      }
      let head = S(p.hi) + S(p.lo)
      let tail = (S(p.hi) - head) + S(p.lo)
      return (head, tail, head.exactDoubles + tail.exactDoubles)
    }
    let x = stored(n.0)
    let y = stored(n.1)
    let z = stored(n.2)
    let offset = differences(v0, origin)
    let distance: S = withUnsafeTemporaryAllocation(
      of: Double.self, capacity: 96
    ) { terms in
      var count = 0
      func append(_ part: Double, _ factor: Double) {
        guard part != 0 && factor != 0 else { return }
        let product = Compensated.twoProduct(part, factor)
        terms[count] = product.product
        terms[count + 1] = product.error
        count += 2
      }
      func append(_ axis: (head: S, tail: S, parts: [Double]), _ d: Pair) {
        if axis.parts.isEmpty {
          let (head, tail) = (Double(axis.head), Double(axis.tail))
          append(head, d.sum)
          append(head, d.error)
          append(tail, d.sum)
          append(tail, d.error)
        } else {
          for part in axis.parts {
            append(part, d.sum)
            append(part, d.error)
          }
        }
      }
      append(x, offset.0)
      append(y, offset.1)
      append(z, offset.2)
      return CameraRelative.roundedSum(
        UnsafeMutableBufferPointer(rebasing: terms[0..<count]))
    }
    let normal = Vector3(x.head, y.head, z.head)
    let tail = Vector3(x.tail, y.tail, z.tail)
    return Exact(
      normal: normal, normalTail: tail, distance: distance,
      isAxisAligned: tail == .zero
        && PlaneIntersection.isAxisAligned(normal))
  }
}
