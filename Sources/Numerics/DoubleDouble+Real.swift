import RealModule
import Geometry
import SceneDescription
import PlatformSupport

// The C library's Double functions (its module is imported for the whole
// package in System/Platform.swift), named at file scope where the names
// are not shadowed by DoubleDouble's static members below.
private func cExp(_ x: Double) -> Double { exp(x) }
private func cExpMinusOne(_ x: Double) -> Double { expm1(x) }
private func cExp2(_ x: Double) -> Double { exp2(x) }
private func cLog(_ x: Double) -> Double { log(x) }
private func cLogOnePlus(_ x: Double) -> Double { log1p(x) }
private func cLog2(_ x: Double) -> Double { log2(x) }
private func cLog10(_ x: Double) -> Double { log10(x) }
private func cSin(_ x: Double) -> Double { sin(x) }
private func cCos(_ x: Double) -> Double { cos(x) }
private func cTan(_ x: Double) -> Double { tan(x) }
private func cAsin(_ x: Double) -> Double { asin(x) }
private func cAcos(_ x: Double) -> Double { acos(x) }
private func cAtan(_ x: Double) -> Double { atan(x) }
private func cAtan2(_ y: Double, _ x: Double) -> Double { atan2(y, x) }
private func cSinh(_ x: Double) -> Double { sinh(x) }
private func cCosh(_ x: Double) -> Double { cosh(x) }
private func cTanh(_ x: Double) -> Double { tanh(x) }
private func cAsinh(_ x: Double) -> Double { asinh(x) }
private func cAcosh(_ x: Double) -> Double { acosh(x) }
private func cAtanh(_ x: Double) -> Double { atanh(x) }
private func cPow(_ x: Double, _ y: Double) -> Double { pow(x, y) }
private func cErf(_ x: Double) -> Double { erf(x) }
private func cErfc(_ x: Double) -> Double { erfc(x) }
private func cGamma(_ x: Double) -> Double { tgamma(x) }
private func cLogGamma(_ x: Double) -> Double { lgamma(x) }

/// The functions of swift-numerics' `Real`, so that DoubleDouble is a Real
/// against both the stand-in RealModule (which requires a subset) and the
/// real package (every member below is one of its requirements or
/// defaults, declared here on the type so neither world is ambiguous).
///
/// Accuracy: `sqrt`, `hypot`, `pow(_:_:)` with an Int exponent, `root`,
/// and `sin`, `cos` and `tan` for |x| < 2³⁰ are double-double accurate
/// (stated on each; the tests' references rotate by them). Every other
/// function is Double's C library function of `hi`, converted exactly: the
/// accuracy of Double only (≈ 2⁻⁵³ relative, or absolute near zeros), not
/// 2⁻¹⁰⁴. The reference path does not use them: it intersects in
/// arithmetic and square roots, its camera rays made in the render's
/// precision. (MaterialTests' reference shading uses `pow(_:_:)` with a
/// real exponent, at Double's accuracy where the reference is this type.)
extension DoubleDouble: Real {
  /// Through Double, for the functions the reference path never uses.
  @inlinable
  static func viaDouble(_ x: DoubleDouble, _ f: (Double) -> Double)
    -> DoubleDouble
  {
    DoubleDouble(f(x.hi))
  }

  // MARK: Double-double accurate

  /// `x.squareRoot()`: ≤ 2u² + O(u³) relative error.
  @usableFromInline
  package static func sqrt(_ x: DoubleDouble) -> DoubleDouble {
    x.squareRoot()
  }

  /// √(x² + y²) in double-double, scaled by a power of two so that the
  /// squares neither overflow nor underflow: ≤ about 8u² relative error.
  /// +∞ if either is infinite, even with a NaN.
  @usableFromInline
  package static func hypot(_ x: DoubleDouble, _ y: DoubleDouble)
    -> DoubleDouble
  {
    if x.isInfinite || y.isInfinite { return .infinity }
    if x.isNaN || y.isNaN { return .nan }
    let larger = Swift.max(x.magnitude, y.magnitude)
    if larger == 0 { return 0 }
    let scale = -larger.exponent
    let a = DoubleDouble(sign: .plus, exponent: scale, significand: x.magnitude)
    let b = DoubleDouble(sign: .plus, exponent: scale, significand: y.magnitude)
    let root = (a * a + b * b).squareRoot()
    return DoubleDouble(sign: .plus, exponent: -scale, significand: root)
  }

  /// xⁿ by repeated squaring, each product ≤ 5u²: relative error ≤
  /// 5u²·(2·log₂|n| + 1) roughly, plus one division for negative n. x⁰ = 1.
  @usableFromInline
  package static func pow(_ x: DoubleDouble, _ n: Int) -> DoubleDouble {
    if n == 0 { return 1 }
    var base = x
    var remaining = n.magnitude
    var result: DoubleDouble = 1
    while remaining > 0 {
      if remaining & 1 == 1 { result = result * base }
      remaining >>= 1
      if remaining > 0 { base = base * base }
    }
    return n < 0 ? 1 / result : result
  }

  /// The real n-th root (odd n: negative x allowed; even n: NaN below
  /// zero): Double's root of `hi`, then one Newton step in double-double,
  /// quadratic from 2⁻⁵³, so a few units of 2⁻¹⁰⁶ for small n.
  @usableFromInline
  package static func root(_ x: DoubleDouble, _ n: Int) -> DoubleDouble {
    guard n != 0 else { return .nan }
    if n == 1 { return x }
    if n == 2 { return x.squareRoot() }
    if n < 0 { return 1 / root(x, -n) }
    if x.isNaN || (x < 0 && n & 1 == 0) { return .nan }
    if x.isZero || x.isInfinite { return x }
    let magnitude = x.magnitude
    let guess = DoubleDouble(cPow(magnitude.hi, 1 / Double(n)))
    guard guess.isFinite, guess != 0 else {
      return DoubleDouble(signOf: x, magnitudeOf: guess)
    }
    // y ← y − (yⁿ − x)/(n·yⁿ⁻¹)
    let power = pow(guess, n - 1)
    let step = (power * guess - magnitude) / (DoubleDouble(n) * power)
    return DoubleDouble(signOf: x, magnitudeOf: guess - step)
  }

  /// 1/x, when it is normal (or x is zero or infinite), as swift-numerics
  /// defines it; ≤ 2u² + O(u³).
  @usableFromInline
  package var reciprocal: DoubleDouble? {
    let inverse = 1 / self
    if inverse.isNormal || isZero || !isFinite { return inverse }
    return nil
  }

  // MARK: Through Double (accuracy of Double only)

  /// Through Double.
  @usableFromInline
  package static func exp(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cExp)
  }
  /// Through Double.
  @usableFromInline
  package static func expMinusOne(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cExpMinusOne)
  }
  /// Through Double.
  @usableFromInline
  package static func exp2(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cExp2)
  }
  /// Through Double (10^x by the C library's pow).
  @usableFromInline
  package static func exp10(_ x: DoubleDouble) -> DoubleDouble {
    DoubleDouble(cPow(10, x.hi))
  }
  /// Through Double.
  @usableFromInline
  package static func log(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cLog)
  }
  /// Through Double.
  @usableFromInline
  package static func log(onePlus x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cLogOnePlus)
  }
  /// Through Double.
  @usableFromInline
  package static func log2(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cLog2)
  }
  /// Through Double.
  @usableFromInline
  package static func log10(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cLog10)
  }
  /// sin x in double-double for |x| < 2³⁰ (see `reducedQuarterTurn`),
  /// within a few units of u² absolute; through Double beyond.
  @usableFromInline
  package static func sin(_ x: DoubleDouble) -> DoubleDouble {
    guard let (r, quadrant) = reducedQuarterTurn(x) else {
      return viaDouble(x, cSin)
    }
    switch quadrant {
    case 0: return sinSeries(r)
    case 1: return cosSeries(r)
    case 2: return -sinSeries(r)
    default: return -cosSeries(r)
    }
  }
  /// cos x in double-double for |x| < 2³⁰, within a few units of u²
  /// absolute; through Double beyond.
  @usableFromInline
  package static func cos(_ x: DoubleDouble) -> DoubleDouble {
    guard let (r, quadrant) = reducedQuarterTurn(x) else {
      return viaDouble(x, cCos)
    }
    switch quadrant {
    case 0: return cosSeries(r)
    case 1: return -sinSeries(r)
    case 2: return -cosSeries(r)
    default: return sinSeries(r)
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

  /// Σ (−1)ⁱ r^(2i+1)/(2i+1)! for |r| ≤ π/4 (plus the reduction's slack),
  /// until the terms fall below 2⁻¹¹⁰ of the sum: at most 14 terms, each
  /// rounded within a few u² of itself.
  static func sinSeries(_ r: DoubleDouble) -> DoubleDouble {
    let square = r * r
    var term = r
    var sum = r
    var n = 1.0
    while term.magnitude > sum.magnitude * 0x1p-110 {
      term = -(term * square) / DoubleDouble((n + 1) * (n + 2))
      n += 2
      sum = sum + term
    }
    return sum
  }

  /// Σ (−1)ⁱ r^(2i)/(2i)! for |r| ≤ π/4, as `sinSeries`.
  static func cosSeries(_ r: DoubleDouble) -> DoubleDouble {
    let square = r * r
    var term: DoubleDouble = 1
    var sum: DoubleDouble = 1
    var n = 0.0
    while term.magnitude > sum.magnitude * 0x1p-110 {
      term = -(term * square) / DoubleDouble((n + 1) * (n + 2))
      n += 2
      sum = sum + term
    }
    return sum
  }
  /// Through Double.
  @usableFromInline
  package static func asin(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cAsin)
  }
  /// Through Double.
  @usableFromInline
  package static func acos(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cAcos)
  }
  /// Through Double.
  @usableFromInline
  package static func atan(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cAtan)
  }
  /// Through Double.
  @usableFromInline
  package static func atan2(y: DoubleDouble, x: DoubleDouble) -> DoubleDouble {
    DoubleDouble(cAtan2(y.hi, x.hi))
  }
  /// Through Double.
  @usableFromInline
  package static func sinh(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cSinh)
  }
  /// Through Double.
  @usableFromInline
  package static func cosh(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cCosh)
  }
  /// Through Double.
  @usableFromInline
  package static func tanh(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cTanh)
  }
  /// Through Double.
  @usableFromInline
  package static func asinh(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cAsinh)
  }
  /// Through Double.
  @usableFromInline
  package static func acosh(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cAcosh)
  }
  /// Through Double.
  @usableFromInline
  package static func atanh(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cAtanh)
  }
  /// Through Double: x^y for real y; NaN for negative x.
  @usableFromInline
  package static func pow(_ x: DoubleDouble, _ y: DoubleDouble)
    -> DoubleDouble
  {
    if x < 0 { return .nan }
    return DoubleDouble(cPow(x.hi, y.hi))
  }
  /// Through Double.
  @usableFromInline
  package static func erf(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cErf)
  }
  /// Through Double.
  @usableFromInline
  package static func erfc(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cErfc)
  }
  /// Through Double.
  @usableFromInline
  package static func gamma(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cGamma)
  }
  /// Through Double: log |Γ(x)|.
  @usableFromInline
  package static func logGamma(_ x: DoubleDouble) -> DoubleDouble {
    viaDouble(x, cLogGamma)
  }
  /// The sign of Γ(x), exactly: + for x ≥ 0 and at the poles, otherwise
  /// alternating between the negative integers.
  @usableFromInline
  package static func signGamma(_ x: DoubleDouble) -> FloatingPointSign {
    if x >= 0 { return .plus }
    let whole = x.rounded(.towardZero)
    if x == whole { return .plus }
    let half = DoubleDouble(sign: .plus, exponent: -1, significand: whole)
    return half.rounded(.towardZero) == half ? .minus : .plus
  }
}
