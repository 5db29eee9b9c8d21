import Geometry

/// A floating-point number held as the unevaluated sum `hi + lo` of two
/// Doubles: the reference precision where the platform has no Float80.
///
/// The model. Every finite value is a binary floating-point number with a
/// 106-bit significand (`significandBitCount` 105 fraction bits after the
/// leading one, so `ulpOfOne` = 2⁻¹⁰⁵) and Double's exponent range: each
/// operation rounds its result to that format, to nearest. The pair is
/// normalised, `hi` = `hi + lo` rounded to Double and |lo| ≤ ulp(hi)/2, so
/// every value has one representation; 106 bits fit because `lo` may take
/// the opposite sign to `hi` (53 + 53 bits, the sign of `lo` being the 54th
/// of the tail). Unlike Float80 this is not IEEE arithmetic: results are
/// accurate to a few units of 2⁻¹⁰⁶, not correctly rounded. With u = 2⁻⁵³
/// (so u² = 2⁻¹⁰⁶), each bound relative to the exact result of the
/// operation on the operands:
/// - `+`, `−`: ≤ 3u²/(1 − 4u) (Joldes, Muller and Popescu, "Tight and
///   rigorous error bounds for basic building blocks of double-word
///   arithmetic", ACM TOMS 44(2), 2017, Algorithm 6), plus u² for the
///   rounding to 106 bits: ≤ 4u² + 12u³ + O(u⁴), one unit of 2⁻¹⁰⁴.
/// - `×`: ≤ 4u² (their Algorithm 12 with fused multiply-adds; the bound as
///   proved by Muller and Rideau, ACM TOMS 48(1), 2022), plus u²: ≤ 5u².
/// - `÷`, `squareRoot()`: Double's quotient or root refined by two Newton
///   steps whose residuals are formed from exact products, so the
///   truncation is O(u³); then the tail's rounding and the rounding to 106
///   bits: ≤ 2u² + O(u³).
/// Measured worst cases (Tests/RayTracerTests/Math/DoubleDoubleTests.swift,
/// against exact results): 1.5u², 2.9u², 1.5u², 1.5u². Products of
/// integers below 2⁵³ are exact (both parts are error-free), and so, as
/// tested, are the quotients back and the roots of their squares.
/// Conversions from Double, Float, Float80 and integers of at most 106
/// significant bits are exact; from wider integers and to narrower types
/// they round correctly (to nearest even).
///
/// Where precision is lost (documented, not hidden by the model):
/// - near overflow: a result whose `hi` would round to infinity overflows,
///   so the largest finite value is 2¹⁰²⁴ − 2⁹⁷⁰ − 2⁹¹⁸, short of the
///   format's 2¹⁰²⁴ − 2⁹¹⁸; intermediate products overflow up to a factor
///   2 earlier, as in Double.
/// - when `lo` is subnormal, below 2⁻⁹⁶⁹: values are multiples of 2⁻¹⁰⁷⁴,
///   so precision falls gradually to Double's at 2⁻¹⁰²² and below; `ulp`
///   and `nextUp` report that real spacing, never less than 2⁻¹⁰⁷⁴. The
///   error terms of products underflow before that, from about 2⁻⁹¹⁶.
/// - literals: `FloatLiteralType` is Double, so `0.1 as DoubleDouble` is
///   Double's 0.1, not 1/10 to 106 bits; write `DoubleDouble(1) / 10`.
/// - elementary functions: only those `RayScalar` asks
///   (DoubleDouble+Elementary.swift): `sin`, `cos`, `tan` double-double
///   accurate for |x| < 2³⁰, `pow` with a real exponent through Double.
///   The reference path uses arithmetic and square roots only; the tests'
///   references also rotate.
/// - `addingProduct` is not fused: it rounds the product, then the sum.
///
/// On x86 the reference path uses Float80 (64-bit significand, IEEE); this
/// type is the reference elsewhere (Apple Silicon) and is tested against
/// Float80 on x86 (Tests/RayTracerTests/Math/DoubleDoubleTests.swift).
@frozen
@usableFromInline
package struct DoubleDouble: Sendable {
  /// The leading part, `hi + lo` rounded to Double. It carries the value's
  /// sign, also for zeros; infinities and NaNs are held in `hi` alone.
  @usableFromInline
  package let hi: Double
  /// The trailing part: |lo| ≤ ulp(hi)/2, zero when `hi` is not finite.
  @usableFromInline
  package let lo: Double

  /// A pair already normalised and in the 106-bit format.
  @inlinable
  init(uncheckedHi hi: Double, lo: Double) {
    self.hi = hi
    self.lo = lo
  }

  /// `hi + lo` rounded to the 106-bit format (exact when it fits: any two
  /// Doubles whose sum spans at most 106 bits).
  @inlinable
  package init(_ hi: Double, _ lo: Double) {
    let (sum, error) = Compensated.twoSum(hi, lo)
    self = Self.normalized(sum, error)
  }

  /// A Double, exactly.
  @inlinable
  package init(_ value: Double) {
    self.init(uncheckedHi: value, lo: 0)
  }
}

// MARK: - Building blocks

extension DoubleDouble {
  /// s + e == a + b exactly, s = fl(a + b), when |a| ≥ |b| or a == 0
  /// (Dekker's Fast2Sum).
  @inlinable
  static func fastTwoSum(_ a: Double, _ b: Double) -> (Double, Double) {
    let s = a + b
    return (s, b - (s - a))
  }

  /// a + b, where fl(a + b) == a or |a| ≥ |b|, normalised and rounded to
  /// the 106-bit format; an overflowing or non-finite sum is returned with
  /// a zero tail.
  @inlinable
  static func normalized(_ a: Double, _ b: Double) -> DoubleDouble {
    let (hi, lo) = fastTwoSum(a, b)
    guard hi.isFinite else {
      // An infinite a stays (b may be an overflow's −∞ or NaN).
      return DoubleDouble(uncheckedHi: a.isFinite ? hi : a, lo: 0)
    }
    guard lo != 0 else { return DoubleDouble(uncheckedHi: hi, lo: 0) }
    // The value's leading bit: one below hi's when hi is a power of two
    // and lo takes the other sign.
    var exponent = Int(hi.exponent)
    if hi.significandBitPattern == 0 && (lo < 0) != (hi < 0) {
      exponent -= 1
    }
    // The format's quantum, never below Double's least subnormal (lo is a
    // Double); dividing by a power of two is exact here, |lo/q| ≤ 2⁵³.
    let quantum = Double(
      sign: .plus, exponent: Swift.max(exponent - 105, -1074),
      significand: 1)
    let roundedLo = (lo / quantum).rounded(.toNearestOrEven) * quantum
    if roundedLo == lo { return DoubleDouble(uncheckedHi: hi, lo: lo) }
    // A tie of lo at ulp(hi)/2 may move hi; the sum stays exact.
    let (h, l) = fastTwoSum(hi, roundedLo)
    return DoubleDouble(uncheckedHi: h, lo: l)
  }

  /// Sum of five Doubles as a pair (Sum2 of Ogita, Rump and Oishi): error
  /// ≤ u·|sum| + γ₄²·Σ|terms|, used for Newton residuals whose terms are
  /// exact.
  @inlinable
  static func sum(
    _ a: Double, _ b: Double, _ c: Double, _ d: Double, _ e: Double
  ) -> (Double, Double) {
    let s1 = Compensated.twoSum(a, b)
    let s2 = Compensated.twoSum(s1.sum, c)
    let s3 = Compensated.twoSum(s2.sum, d)
    let s4 = Compensated.twoSum(s3.sum, e)
    let error = s1.error + s2.error + s3.error + s4.error
    return fastTwoSum(s4.sum, error)
  }

  /// q0 + q1 + q2 rounded to the format, where the parts decrease by about
  /// 2⁵³ each (the quotient or root's Newton steps): one rounding of
  /// q1 + q2's tail, then the rounding to 106 bits.
  @inlinable
  static func renormalized(_ q0: Double, _ q1: Double, _ q2: Double)
    -> DoubleDouble
  {
    let (s, e) = fastTwoSum(q0, q1)
    guard s.isFinite else { return DoubleDouble(uncheckedHi: s, lo: 0) }
    let (t, f) = Compensated.twoSum(e, q2)
    let (h, l) = fastTwoSum(s, t)
    return normalized(h, l + f)
  }
}

// MARK: - Arithmetic

extension DoubleDouble {
  /// x + y, ≤ 4u² + 13u³ relative error (see the type's comment).
  @inlinable
  package static func + (x: DoubleDouble, y: DoubleDouble) -> DoubleDouble {
    let (sh, sl) = Compensated.twoSum(x.hi, y.hi)
    guard sh.isFinite else { return DoubleDouble(uncheckedHi: sh, lo: 0) }
    let (th, tl) = Compensated.twoSum(x.lo, y.lo)
    let c = sl + th
    let (vh, vl) = fastTwoSum(sh, c)
    let result = normalized(vh, tl + vl)
    // An exact zero takes IEEE's sign: −0 only for −0 + −0.
    if result.hi == 0 {
      return DoubleDouble(uncheckedHi: sh == 0 ? sh : 0, lo: 0)
    }
    return result
  }

  @inlinable
  package static prefix func - (x: DoubleDouble) -> DoubleDouble {
    DoubleDouble(uncheckedHi: -x.hi, lo: -x.lo)
  }

  @inlinable
  package static func - (x: DoubleDouble, y: DoubleDouble) -> DoubleDouble {
    x + -y
  }

  /// x·y, ≤ 5u² relative error (see the type's comment).
  @inlinable
  package static func * (x: DoubleDouble, y: DoubleDouble) -> DoubleDouble {
    let (ch, cl1) = Compensated.twoProduct(x.hi, y.hi)
    guard ch.isFinite, ch != 0 else {
      return DoubleDouble(uncheckedHi: ch, lo: 0)
    }
    let tl1 = x.lo * y.lo
    let tl2 = tl1.addingProduct(x.hi, y.lo)
    let cl2 = tl2.addingProduct(x.lo, y.hi)
    return normalized(ch, cl1 + cl2)
  }

  /// x/y by three Newton steps q ← q + (x − q·y)/y, each residual computed
  /// from exact products: ≤ 2u² + O(u³) relative error.
  @inlinable
  package static func / (x: DoubleDouble, y: DoubleDouble) -> DoubleDouble {
    let q0 = x.hi / y.hi
    guard q0.isFinite, q0 != 0, y.hi.isFinite else {
      return DoubleDouble(uncheckedHi: q0, lo: 0)
    }
    // r = x − q0·y: x.hi − q0·y.hi is exact (Sterbenz), the rest is made
    // of exact products and summed in twice the precision.
    let (p0, e0) = Compensated.twoProduct(q0, y.hi)
    let (p1, e1) = Compensated.twoProduct(q0, y.lo)
    let (r0, r0Tail) = sum(x.hi - p0, x.lo, -e0, -p1, -e1)
    let q1 = r0 / y.hi
    let (p2, e2) = Compensated.twoProduct(q1, y.hi)
    let (p3, e3) = Compensated.twoProduct(q1, y.lo)
    let (r1, _) = sum(r0 - p2, r0Tail, -e2, -p3, -e3)
    let q2 = r1 / y.hi
    return renormalized(q0, q1, q2)
  }

  /// √x by two Newton steps s ← s + (x − s²)/(2s) from Double's correctly
  /// rounded root, residuals from exact products: ≤ 2u² + O(u³) relative
  /// error; −0 for −0, NaN below zero.
  @inlinable
  package func squareRoot() -> DoubleDouble {
    guard hi > 0, hi.isFinite else {
      return DoubleDouble(uncheckedHi: hi.squareRoot(), lo: 0)
    }
    let s0 = hi.squareRoot()
    let (p0, e0) = Compensated.twoProduct(s0, s0)
    let (r0, r0Tail) = DoubleDouble.sum(hi - p0, lo, -e0, 0, 0)
    let twiceRoot = 2 * s0
    let s1 = r0 / twiceRoot
    // x − (s0 + s1)² = r0 − 2·s0·s1 − s1², the first product exact.
    let (p1, e1) = Compensated.twoProduct(twiceRoot, s1)
    let (r1, _) = DoubleDouble.sum(r0 - p1, r0Tail, -e1, -(s1 * s1), 0)
    let s2 = r1 / twiceRoot
    return DoubleDouble.renormalized(s0, s1, s2)
  }
}

// MARK: - Comparison

extension DoubleDouble: Equatable, Hashable {
  /// IEEE equality: NaN is unequal to everything, −0 == +0. Exact, since
  /// every value has one normalised pair.
  @inlinable
  package static func == (x: DoubleDouble, y: DoubleDouble) -> Bool {
    x.hi == y.hi && x.lo == y.lo
  }

  @inlinable
  package func hash(into hasher: inout Hasher) {
    // Double hashes −0 as +0, as == requires.
    hasher.combine(hi)
    hasher.combine(lo)
  }
}

extension DoubleDouble: Comparable {
  /// Exact: hi decides unless equal, then lo.
  @inlinable
  package static func < (x: DoubleDouble, y: DoubleDouble) -> Bool {
    x.hi < y.hi || (x.hi == y.hi && x.lo < y.lo)
  }
}

extension DoubleDouble: CustomStringConvertible {
  /// "hi + lo" (or "hi − |lo|"), each part printed as Double prints it.
  @usableFromInline
  package var description: String {
    guard lo != 0 else { return hi.description }
    return lo < 0
      ? "\(hi) - \((-lo).description)" : "\(hi) + \(lo.description)"
  }
}
