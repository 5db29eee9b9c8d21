/// Sums of Double terms held exactly, as Shewchuk's expansions ("Adaptive
/// Precision Floating-Point Arithmetic and Fast Robust Geometric
/// Predicates", Discrete Comput. Geom. 18, 1997): the sum is kept as
/// non-overlapping components in increasing magnitude, each addition
/// carried through them by `Compensated.twoSum`, so nothing is ever
/// rounded away. Products enter as the two terms of
/// `Compensated.twoProduct`.
///
/// Used where a determinant must be known beyond any working precision:
/// the normal of a large or thin triangle (`TrianglePlane.exact`), computed
/// once per such triangle when a scene is compiled. Exact while no component is
/// subnormal or infinite (`LengthScale` keeps a compiled scene's lengths
/// within 2^±255 of 1 in Double, whose products of three lengths stay far
/// inside the range).
public struct ExactSum {
  @usableFromInline var components: [Double] = []

  @inlinable public init() { components.reserveCapacity(16) }

  /// Adds `term` exactly (Shewchuk's Grow-Expansion, zeros dropped).
  @inlinable
  public mutating func add(_ term: Double) {
    guard term != 0 else { return }
    var carry = term
    var kept = 0
    for index in components.indices {
      let (sum, error) = Compensated.twoSum(carry, components[index])
      carry = sum
      if error != 0 {
        components[kept] = error
        kept += 1
      }
    }
    components.removeSubrange(kept...)
    if carry != 0 { components.append(carry) }
  }

  /// Adds a·b exactly.
  @inlinable
  public mutating func add(_ a: Double, times b: Double) {
    let product = Compensated.twoProduct(a, b)
    add(product.error)
    add(product.product)
  }

  @inlinable public var isZero: Bool { components.isEmpty }

  /// The sum as hi + lo, |lo| ≤ ulp(hi), and within a relative 2⁻¹⁰⁴ of
  /// the exact sum: hi is the components added from the smallest (within
  /// an ulp or two of the sum, since they do not overlap), lo the exact
  /// remainder's components added the same way.
  @inlinable
  public var pair: (hi: Double, lo: Double) {
    let hi = estimate
    var remainder = self
    remainder.add(-hi)
    let lo = remainder.estimate
    let renormalised = Compensated.twoSum(hi, lo)
    return (renormalised.sum, renormalised.error)
  }

  /// The components added from the smallest.
  @inlinable
  public var estimate: Double {
    var total = 0.0
    for component in components { total += component }
    return total
  }

}

extension RayScalar {
  /// The value as Doubles whose sum it is exactly: one for Float and
  /// Double, two or three for the reference path's Float80 and
  /// DoubleDouble. Empty for zero.
  @inlinable
  public var exactDoubles: [Double] {
    var rest = self
    var parts: [Double] = []
    while rest != 0 && rest.isFinite && parts.count < 4 {
      let part = Double(rest)
      parts.append(part)
      rest -= Self(part)
    }
    return parts
  }
}
