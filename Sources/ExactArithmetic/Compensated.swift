import Geometry

/// Error-free transformations and the sums and dot products built on them
/// (Ogita, Rump and Oishi, "Accurate sum and dot product", SIAM J. Sci.
/// Comput. 26(6), 2005): results as if computed in twice the working precision
/// and then rounded once.
///
/// They run where cancellation would otherwise lose every digit: the
/// camera-relative sphere constants |p|² − r² of a planet seen from one unit
/// above it, and the denominator n·d of a plane seen at a grazing angle.
@usableFromInline
package enum Compensated {
  /// s + e == a + b exactly, with s = fl(a + b) (Knuth's TwoSum, no branch).
  @inlinable
  package static func twoSum<S: RayScalar>(_ a: S, _ b: S) -> (sum: S, error: S)
  {
    let s = a + b
    let bVirtual = s - a
    let aVirtual = s - bVirtual
    return (s, (a - aVirtual) + (b - bVirtual))
  }

  /// p + e == a·b exactly, with p = fl(a·b).
  ///
  /// A Float product is exact in Double, which is cheaper than the fused
  /// multiply-add: without FMA in the baseline x86-64 instruction set,
  /// `addingProduct` is a call into libm. For Double that call measured
  /// faster than Dekker and Veltkamp's 17-flop split, so it stays here,
  /// valid at any magnitude; the per-ray `dot` of planes, on unit
  /// vectors, uses `splitProduct` (docs/PERFORMANCE.md, "The cost of
  /// working across the whole range").
  @inlinable @inline(__always)
  package static func twoProduct<S: RayScalar>(
    _ a: S, _ b: S
  ) -> (product: S, error: S) {
    if S.self == Float.self {
      let exact = Double(a) * Double(b)
      let p = S(exact)
      return (p, S(exact - Double(p)))
    }
    let p = a * b
    return (p, (-p).addingProduct(a, b))
  }

  /// p + e == a·b exactly, p = fl(a·b), by Dekker's product of Veltkamp's
  /// halves (17 flops, no call): exact while |a|, |b| < 2^(E/2) and the
  /// error term is not subnormal; for Float, `twoProduct`'s Double
  /// product. Outside that range use `twoProduct`.
  @inlinable @inline(__always)
  package static func splitProduct<S: RayScalar>(
    _ a: S, _ b: S
  ) -> (product: S, error: S) {
    if S.self == Float.self { return twoProduct(a, b) }
    let p = a * b
    let (aHigh, aLow) = split(a)
    let (bHigh, bLow) = split(b)
    let error =
      ((aHigh * bHigh - p) + aHigh * bLow + aLow * bHigh) + aLow * bLow
    return (p, error)
  }

  /// Veltkamp's split of a into high + low, each with at most half the
  /// significand's bits, high + low == a exactly (for |a| < 2^(E/2)).
  @inlinable @inline(__always)
  static func split<S: RayScalar>(_ a: S) -> (high: S, low: S) {
    let factor =
      S(
        sign: .plus, exponent: S.Exponent((S.significandBitCount + 2) / 2),
        significand: 1) + 1
    let c = factor * a
    let high = c - (c - a)
    return (high, a - high)
  }

  /// a·b, as if evaluated in twice the precision and rounded (Dot2).
  ///
  /// Relative error ≤ ε + γ(n)²·cond: a few ulps unless the dot product
  /// cancels by more than 1/ε, where plain evaluation would already have
  /// no correct digit left.
  ///
  /// The products' errors come from Dekker and Veltkamp's splitting
  /// (`splitProduct`) rather than the fused multiply-add, which baseline
  /// x86-64 reaches only through a libm call: the same exact errors, so
  /// the same results, for components of magnitude below 2^(E/2) (E the
  /// type's largest exponent) and products above the subnormal range, as
  /// the unit normals and directions of the render's planes are.
  @inlinable
  package static func dot<S: RayScalar>(
    _ a: Vector3<S>, _ b: Vector3<S>
  ) -> S {
    let px = splitProduct(a.x, b.x)
    let py = splitProduct(a.y, b.y)
    let pz = splitProduct(a.z, b.z)
    let s1 = twoSum(px.product, py.product)
    let s2 = twoSum(s1.sum, pz.product)
    let errors = px.error + py.error + pz.error + s1.error + s2.error
    return s2.sum + errors
  }

  /// Σ terms, as if evaluated in twice the precision and rounded (Sum2).
  @inlinable
  package static func sum<Terms: Sequence>(_ terms: Terms) -> Terms.Element
  where Terms.Element: RayScalar {
    let pair = sumPair(terms)
    return pair.sum + pair.error
  }

  /// Σ terms as an unevaluated pair sum + error with |error| ≤ ulp(sum)/2,
  /// as if evaluated in twice the precision (Sum2 with its last addition
  /// renormalised by twoSum).
  @inlinable
  package static func sumPair<Terms: Sequence>(
    _ terms: Terms
  ) -> (sum: Terms.Element, error: Terms.Element)
  where Terms.Element: RayScalar {
    var total: Terms.Element = 0
    var errors: Terms.Element = 0
    for term in terms {
      let step = twoSum(total, term)
      total = step.sum
      errors += step.error
    }
    return twoSum(total, errors)
  }

  /// sum + error rounded once to the narrower type S, where S(sum + error)
  /// would round twice: when sum lies exactly halfway between two S values,
  /// the sign of `error` (not ties-to-even) decides. Elsewhere |error| ≤
  /// ulp(sum)/2 cannot move sum across a midpoint of S, which lies a whole
  /// ulp of Input away or more, so S(sum) is already correct.
  @inlinable
  package static func narrow<Input: RayScalar, S: RayScalar>(
    _ sum: Input, _ error: Input, to _: S.Type = S.self
  ) -> S {
    let rounded = S(sum)
    guard error != 0, rounded.isFinite else { return rounded }
    let difference = sum - Input(rounded)
    guard difference != 0 else { return rounded }
    let neighbour = difference > 0 ? rounded.nextUp : rounded.nextDown
    // The midpoint of two adjacent S values is exact in the wider Input.
    let midpoint = (Input(rounded) + Input(neighbour)) / 2
    guard sum == midpoint else { return rounded }
    return (error > 0) == (difference > 0) ? neighbour : rounded
  }
}
