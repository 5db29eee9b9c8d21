import Geometry

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
@usableFromInline
package struct ExactSum {
  /// The components, in increasing magnitude, in `storage[0..<count]`.
  @usableFromInline var storage: [Double]
  @usableFromInline var count = 0

  /// Room for `capacity` components to start with (a sum of n terms never
  /// has more than n); it grows if needed.
  @inlinable
  package init(capacity: Int = 16) {
    storage = Array(repeating: 0, count: capacity)
  }

  /// Back to zero, its storage kept for the next sum.
  @inlinable
  package mutating func removeAll() { count = 0 }

  /// The components, smallest first.
  @inlinable package var components: ArraySlice<Double> { storage[0..<count] }

  /// Adds `term` exactly (Shewchuk's Grow-Expansion, zeros dropped), in
  /// place.
  @inlinable
  package mutating func add(_ term: Double) {
    guard term != 0 else { return }
    if count == storage.count { storage += repeatElement(0, count: count) }
    let length = count
    count = storage.withUnsafeMutableBufferPointer { e in
      var carry = term
      var kept = 0
      for index in 0..<length {
        let (sum, error) = Compensated.twoSum(carry, e[index])
        carry = sum
        if error != 0 {
          e[kept] = error
          kept += 1
        }
      }
      if carry != 0 {
        e[kept] = carry
        kept += 1
      }
      return kept
    }
  }

  /// Adds a·b exactly.
  @inlinable
  package mutating func add(_ a: Double, times b: Double) {
    let product = Compensated.twoProduct(a, b)
    add(product.error)
    add(product.product)
  }

  @inlinable package var isZero: Bool { count == 0 }

  /// The sum as hi + lo with |lo| ≤ ulp(hi)/2, within a relative 2⁻¹⁰⁴ of
  /// the exact sum: the components added from the smallest with their
  /// errors gathered (Sum2), whose only error is in the gathered errors,
  /// themselves below an ulp of each partial sum of non-overlapping
  /// components.
  @inlinable
  package var pair: (hi: Double, lo: Double) {
    var total = 0.0
    var errors = 0.0
    for index in 0..<count {
      let step = Compensated.twoSum(total, storage[index])
      total = step.sum
      errors += step.error
    }
    let renormalised = Compensated.twoSum(total, errors)
    return (renormalised.sum, renormalised.error)
  }
}

extension RayScalar {
  /// The value as Doubles whose sum it is exactly: one for Float and
  /// Double, two or three for the reference path's Float80 and
  /// DoubleDouble. Empty for zero.
  @inlinable
  package var exactDoubles: [Double] {
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
