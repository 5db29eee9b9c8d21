import Geometry
import PlatformSupport

// The C library's Double functions (its module is imported for the whole
// package by PlatformSupport's Platform.swift), named at file scope where
// the names are not shadowed by DoubleDouble's static members below.
private func cSin(_ x: Double) -> Double { sin(x) }
private func cCos(_ x: Double) -> Double { cos(x) }
private func cTan(_ x: Double) -> Double { tan(x) }
private func cPow(_ x: Double, _ y: Double) -> Double { pow(x, y) }

/// The elementary functions a render asks of its scalar (`RayScalar`):
/// `sin`, `cos` and `tan` in double-double for |x| < 2³⁰ (the tests'
/// references rotate by them), `pow` with a real exponent through Double
/// (≈ 2⁻⁵³ relative, not 2⁻¹⁰⁴). The reference path uses none of them: it
/// intersects in arithmetic and square roots, its camera rays made in the
/// render's precision. (MaterialTests' reference shading uses `pow`, at
/// Double's accuracy where the reference is this type.)
extension DoubleDouble: RayScalar {
  /// Double's function of `hi`, beyond the double-double ranges.
  @inlinable
  static func viaDouble(_ x: DoubleDouble, _ f: (Double) -> Double)
    -> DoubleDouble
  {
    DoubleDouble(f(x.hi))
  }

  /// sin x in double-double for |x| < 2³⁰ (see `reducedQuarterTurn`),
  /// within a few units of u² absolute; through Double beyond.
  @usableFromInline
  package static func sin(_ x: DoubleDouble) -> DoubleDouble {
    guard let (r, quadrant) = reducedQuarterTurn(x) else {
      return viaDouble(x, cSin)
    }
    return sine(r, quarterTurns: quadrant)
  }
  /// cos x = sin(x + π/2), in double-double for |x| < 2³⁰, within a few
  /// units of u² absolute; through Double beyond.
  @usableFromInline
  package static func cos(_ x: DoubleDouble) -> DoubleDouble {
    guard let (r, quadrant) = reducedQuarterTurn(x) else {
      return viaDouble(x, cCos)
    }
    return sine(r, quarterTurns: quadrant + 1)
  }
  /// sin(r + k·π/2) for a reduced r: sin's or cos's series, signed.
  static func sine(_ r: DoubleDouble, quarterTurns k: Int) -> DoubleDouble {
    switch k % 4 {
    case 0: return sinSeries(r)
    case 1: return cosSeries(r)
    case 2: return -sinSeries(r)
    default: return -cosSeries(r)
    }
  }
  /// sin x / cos x, in double-double for |x| < 2³⁰.
  @usableFromInline
  package static func tan(_ x: DoubleDouble) -> DoubleDouble {
    guard reducedQuarterTurn(x) != nil else { return viaDouble(x, cTan) }
    return sin(x) / cos(x)
  }

  /// x − k·π/2 and k mod 4 with k the nearest integer to x/(π/2), by π/2
  /// in three Doubles (159 bits, Cody and Waite): the first two products
  /// are exact and the third's rounding is below 2⁻¹⁶⁰·|k|, so r is within
  /// a few units of u²·|r| + 2⁻¹³⁰ for |x| < 2³⁰. nil beyond, or for
  /// non-finite x.
  static func reducedQuarterTurn(
    _ x: DoubleDouble
  ) -> (DoubleDouble, quadrant: Int)? {
    guard x.isFinite, x.hi.magnitude < 0x1p30 else { return nil }
    let k = (x.hi * 0x1.45f3_06dc_9c88_3p-1).rounded(.toNearestOrEven)
    let p1 = Compensated.twoProduct(k, 0x1.921f_b544_42d1_8p0)
    let p2 = Compensated.twoProduct(k, 0x1.1a62_6331_45c0_7p-54)
    let p3 = k * -0x1.f197_6b7e_d8fb_cp-110
    let r =
      x - DoubleDouble(p1.product, p1.error)
      - DoubleDouble(p2.product, p2.error) - DoubleDouble(p3)
    return (r, (Int(k) % 4 + 4) % 4)
  }

  /// sin r = Σ (−1)ⁱ r^(2i+1)/(2i+1)! for |r| ≤ π/4 (plus the
  /// reduction's slack); see `series`.
  static func sinSeries(_ r: DoubleDouble) -> DoubleDouble {
    series(r, first: r, power: 1)
  }

  /// cos r = Σ (−1)ⁱ r^(2i)/(2i)! for |r| ≤ π/4; see `series`.
  static func cosSeries(_ r: DoubleDouble) -> DoubleDouble {
    series(r, first: 1, power: 0)
  }

  /// Σ (−1)ⁱ r^(2i+n)/(2i+n)! from the term `first` = rⁿ/n!, until the
  /// terms fall below 2⁻¹¹⁰ of the sum: at most 14 terms, each rounded
  /// within a few u² of itself.
  static func series(
    _ r: DoubleDouble, first: DoubleDouble, power n: Double
  ) -> DoubleDouble {
    let square = r * r
    var term = first
    var sum = first
    var k = n
    while term.magnitude > sum.magnitude * 0x1p-110 {
      term = -(term * square) / DoubleDouble((k + 1) * (k + 2))
      k += 2
      sum = sum + term
    }
    return sum
  }
  /// Through Double: x^y for real y; NaN for negative x.
  @usableFromInline
  package static func pow(_ x: DoubleDouble, _ y: DoubleDouble)
    -> DoubleDouble
  {
    if x < 0 { return .nan }
    return DoubleDouble(cPow(x.hi, y.hi))
  }
}
