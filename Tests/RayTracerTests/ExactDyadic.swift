import SceneModel

/// Exact arithmetic on dyadic rationals m·2^e (m an integer of any size),
/// for the tests' references: every Double and Float is one, and so is
/// every sum, difference and product of them, so determinants of the
/// scene's own numbers are found with no rounding at all. Independent of
/// the project's error-free transformations (`Compensated`, `ExactSum`),
/// which it checks: plain schoolbook arithmetic on 32-bit limbs.
struct ExactDyadic: CustomStringConvertible {
  /// Magnitude, least significant limb first, no leading zero limbs.
  var limbs: [UInt32]
  var negative: Bool
  var exponent: Int

  static let zero = ExactDyadic(limbs: [], negative: false, exponent: 0)

  init(limbs: [UInt32], negative: Bool, exponent: Int) {
    var limbs = limbs
    while limbs.last == 0 { limbs.removeLast() }
    self.limbs = limbs
    self.negative = limbs.isEmpty ? false : negative
    self.exponent = limbs.isEmpty ? 0 : exponent
  }

  init(_ value: Double) {
    precondition(value.isFinite)
    guard value != 0 else {
      self = .zero
      return
    }
    // value = significand · 2^(exponent − 52) with an integer significand.
    let bits: UInt64 =
      value.isNormal
      ? value.significandBitPattern | (1 << 52) : value.significandBitPattern
    let exponent =
      value.isNormal ? Int(value.exponent) - 52 : -1074
    self.init(
      limbs: [UInt32(truncatingIfNeeded: bits), UInt32(bits >> 32)],
      negative: value < 0, exponent: exponent)
  }

  init(_ value: Float) { self.init(Double(value)) }

  var isZero: Bool { limbs.isEmpty }
  var signum: Int { isZero ? 0 : (negative ? -1 : 1) }

  /// The magnitude shifted left by `bits`.
  private static func shifted(_ limbs: [UInt32], by bits: Int) -> [UInt32] {
    guard bits > 0, !limbs.isEmpty else { return limbs }
    let whole = bits / 32
    let part = UInt32(bits % 32)
    var result = [UInt32](repeating: 0, count: whole)
    var carry: UInt32 = 0
    for limb in limbs {
      if part == 0 {
        result.append(limb)
      } else {
        result.append((limb << part) | carry)
        carry = limb >> (32 - part)
      }
    }
    if carry != 0 { result.append(carry) }
    return result
  }

  private static func compare(_ a: [UInt32], _ b: [UInt32]) -> Int {
    if a.count != b.count { return a.count < b.count ? -1 : 1 }
    for index in stride(from: a.count - 1, through: 0, by: -1)
    where a[index] != b[index] {
      return a[index] < b[index] ? -1 : 1
    }
    return 0
  }

  private static func add(_ a: [UInt32], _ b: [UInt32]) -> [UInt32] {
    var result: [UInt32] = []
    var carry: UInt64 = 0
    for index in 0..<Swift.max(a.count, b.count) {
      let sum =
        UInt64(index < a.count ? a[index] : 0)
        + UInt64(index < b.count ? b[index] : 0) + carry
      result.append(UInt32(truncatingIfNeeded: sum))
      carry = sum >> 32
    }
    if carry != 0 { result.append(UInt32(carry)) }
    return result
  }

  /// a − b for a ≥ b.
  private static func subtract(_ a: [UInt32], _ b: [UInt32]) -> [UInt32] {
    var result: [UInt32] = []
    var borrow: Int64 = 0
    for index in 0..<a.count {
      var difference =
        Int64(a[index]) - Int64(index < b.count ? b[index] : 0) - borrow
      borrow = 0
      if difference < 0 {
        difference += 1 << 32
        borrow = 1
      }
      result.append(UInt32(difference))
    }
    return result
  }

  static func + (a: ExactDyadic, b: ExactDyadic) -> ExactDyadic {
    if a.isZero { return b }
    if b.isZero { return a }
    let exponent = Swift.min(a.exponent, b.exponent)
    let x = shifted(a.limbs, by: a.exponent - exponent)
    let y = shifted(b.limbs, by: b.exponent - exponent)
    if a.negative == b.negative {
      return ExactDyadic(
        limbs: add(x, y), negative: a.negative, exponent: exponent)
    }
    switch compare(x, y) {
    case 0: return .zero
    case 1:
      return ExactDyadic(
        limbs: subtract(x, y), negative: a.negative, exponent: exponent)
    default:
      return ExactDyadic(
        limbs: subtract(y, x), negative: b.negative, exponent: exponent)
    }
  }

  static prefix func - (a: ExactDyadic) -> ExactDyadic {
    ExactDyadic(limbs: a.limbs, negative: !a.negative, exponent: a.exponent)
  }

  static func - (a: ExactDyadic, b: ExactDyadic) -> ExactDyadic { a + -b }

  static func * (a: ExactDyadic, b: ExactDyadic) -> ExactDyadic {
    if a.isZero || b.isZero { return .zero }
    var result = [UInt32](repeating: 0, count: a.limbs.count + b.limbs.count)
    for (i, x) in a.limbs.enumerated() {
      var carry: UInt64 = 0
      for (j, y) in b.limbs.enumerated() {
        let product = UInt64(x) * UInt64(y) + UInt64(result[i + j]) + carry
        result[i + j] = UInt32(truncatingIfNeeded: product)
        carry = product >> 32
      }
      var position = i + b.limbs.count
      while carry != 0 {
        let sum = UInt64(result[position]) + carry
        result[position] = UInt32(truncatingIfNeeded: sum)
        carry = sum >> 32
        position += 1
      }
    }
    return ExactDyadic(
      limbs: result, negative: a.negative != b.negative,
      exponent: a.exponent + b.exponent)
  }

  /// The number of significant bits of the magnitude.
  private var bitLength: Int {
    guard let top = limbs.last else { return 0 }
    return (limbs.count - 1) * 32 + (32 - top.leadingZeroBitCount)
  }

  /// The top 64 bits of the magnitude (truncated) and the power of two
  /// they stand for: magnitude ≈ top · 2^shift, with shift ≥ 0.
  private var top64: (top: UInt64, shift: Int) {
    let length = bitLength
    let drop = Swift.max(0, length - 64)
    var top: UInt64 = 0
    for bit in stride(from: length - 1, through: drop, by: -1) {
      let limb = limbs[bit / 32]
      top = (top << 1) | UInt64((limb >> UInt32(bit % 32)) & 1)
    }
    return (top, drop)
  }

  /// The value to within a relative 2⁻⁶³ (truncated to 64 bits, then
  /// rounded to Double), as a Double times 2^scale so that values beyond
  /// Double's range still compare.
  var approximation: (value: Double, scale: Int) {
    guard !isZero else { return (0, 0) }
    let (top, shift) = top64
    let value = Double(top) * (negative ? -1 : 1)
    return (value, shift + exponent)
  }

  /// The value rounded to Double (to within an ulp: the truncation to 64
  /// bits is then rounded once more), nil beyond Double's range.
  var double: Double {
    let (value, scale) = approximation
    return Double(sign: .plus, exponent: scale, significand: value)
  }

  /// a / b to within a relative 2⁻¹⁰⁰, as a DoubleDouble-like pair
  /// hi + lo: each quotient digit found from the 64-bit tops and the
  /// remainder computed exactly, three times.
  static func quotient(_ a: ExactDyadic, _ b: ExactDyadic) -> (
    hi: Double, lo: Double
  ) {
    precondition(!b.isZero)
    var remainder = a
    var parts: [Double] = []
    let (bTop, bScale) = b.approximation
    for _ in 0..<3 {
      guard !remainder.isZero else { break }
      let (rTop, rScale) = remainder.approximation
      let digit = Double(
        sign: .plus, exponent: rScale - bScale, significand: rTop / bTop)
      parts.append(digit)
      remainder = remainder - ExactDyadic(digit) * b
    }
    // The parts fall by 2⁻⁵² or more each: hi the first, lo the rest,
    // renormalised.
    let rest = parts.dropFirst().reduce(0, +)
    let hi = parts.first ?? 0
    let sum = hi + rest
    return (sum, rest - (sum - hi))
  }

  var description: String {
    let (value, scale) = approximation
    return "\(value)·2^\(scale)"
  }
}

/// The exact t at which the ray from `origin` along `direction` meets the
/// plane of triangle (v0, v1, v2), det[e1, e2, v0 − o] / det[e1, e2, d]
/// with e1 = v1 − v0, e2 = v2 − v0, and the ray's barycentric weights of
/// v0, v1, v2 (each d·((vⱼ − o) × (vₖ − o)) over their sum, to a few
/// ulps): every entry and product exact. Nil for a ray parallel to the
/// plane or a degenerate triangle.
func exactTriangleT(
  _ v0: Vector3<Double>, _ v1: Vector3<Double>, _ v2: Vector3<Double>,
  origin: Vector3<Double>, direction: Vector3<Double>
) -> (hi: Double, lo: Double, weights: (Double, Double, Double))? {
  typealias Exact3 = [ExactDyadic]
  func exact(_ v: Vector3<Double>) -> Exact3 {
    [ExactDyadic(v.x), ExactDyadic(v.y), ExactDyadic(v.z)]
  }
  func minus(_ a: Exact3, _ b: Exact3) -> Exact3 { (0..<3).map { a[$0] - b[$0] } }
  func cross(_ a: Exact3, _ b: Exact3) -> Exact3 {
    [
      a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
      a[0] * b[1] - a[1] * b[0],
    ]
  }
  func dot(_ a: Exact3, _ b: Exact3) -> ExactDyadic {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
  }
  let (p0, p1, p2, o, d) = (
    exact(v0), exact(v1), exact(v2), exact(origin), exact(direction)
  )
  let n = cross(minus(p1, p0), minus(p2, p0))
  let numerator = dot(n, minus(p0, o))
  let denominator = dot(n, d)
  guard !denominator.isZero else { return nil }
  let t = ExactDyadic.quotient(numerator, denominator)
  let (q0, q1, q2) = (minus(p0, o), minus(p1, o), minus(p2, o))
  let sum = denominator.double
  let weights = (
    dot(d, cross(q1, q2)).double / sum, dot(d, cross(q2, q0)).double / sum,
    dot(d, cross(q0, q1)).double / sum
  )
  return (t.hi, t.lo, weights)
}
