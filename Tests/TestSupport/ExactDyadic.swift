import Geometry
import ExactArithmetic

/// An exact binary rational m·2ᵉ (m an integer of any size): sums,
/// differences and products of Doubles and Floats with no rounding at
/// all, for references that must not share a rounding with the code they
/// check (`ExactEllipsoid`). Schoolbook arithmetic on 32-bit limbs: slow,
/// simple, and exact.
package struct ExactDyadic: CustomStringConvertible {
  /// |m|, little-endian 32-bit limbs, no trailing zero limb; [] for 0.
  package var limbs: [UInt32]
  package var negative: Bool
  package var exponent: Int

  package static let zero = ExactDyadic(limbs: [], negative: false, exponent: 0)

  package init(limbs: [UInt32], negative: Bool, exponent: Int) {
    var limbs = limbs
    while limbs.last == 0 { limbs.removeLast() }
    self.limbs = limbs
    self.negative = limbs.isEmpty ? false : negative
    self.exponent = exponent
  }

  /// `value` exactly (finite).
  package init(_ value: Double) {
    precondition(value.isFinite, "only finite values are exact")
    guard value != 0 else {
      self = .zero
      return
    }
    // value = significand · 2^(exponent − 52), the significand an integer.
    let integer: UInt64 =
      value.isNormal
      ? value.significandBitPattern | (1 << 52) : value.significandBitPattern
    let exponent =
      (value.isNormal
        ? Int(value.exponent) : Int(Double.leastNormalMagnitude.exponent))
      - 52
    self.init(
      limbs: [UInt32(truncatingIfNeeded: integer), UInt32(integer >> 32)],
      negative: value < 0, exponent: exponent)
  }

  package init(_ value: Float) { self.init(Double(value)) }

  package var isZero: Bool { limbs.isEmpty }
  package var signum: Int { isZero ? 0 : (negative ? -1 : 1) }

  /// The number of bits of |m|.
  package var bitWidth: Int {
    guard let top = limbs.last else { return 0 }
    return limbs.count * 32 - top.leadingZeroBitCount
  }

  package var description: String {
    "\(negative ? "-" : "")\(ScaledDoubleDouble(self))"
  }

  package static prefix func - (x: ExactDyadic) -> ExactDyadic {
    ExactDyadic(limbs: x.limbs, negative: !x.negative, exponent: x.exponent)
  }

  package static func * (x: ExactDyadic, y: ExactDyadic) -> ExactDyadic {
    guard !x.isZero, !y.isZero else { return .zero }
    var product = [UInt32](repeating: 0, count: x.limbs.count + y.limbs.count)
    for (i, a) in x.limbs.enumerated() {
      var carry: UInt64 = 0
      for (j, b) in y.limbs.enumerated() {
        let sum = UInt64(a) * UInt64(b) + UInt64(product[i + j]) + carry
        product[i + j] = UInt32(truncatingIfNeeded: sum)
        carry = sum >> 32
      }
      product[i + y.limbs.count] = UInt32(carry)
    }
    return ExactDyadic(
      limbs: product, negative: x.negative != y.negative,
      exponent: x.exponent + y.exponent)
  }

  package static func + (x: ExactDyadic, y: ExactDyadic) -> ExactDyadic {
    if x.isZero { return y }
    if y.isZero { return x }
    // Both to the smaller exponent: the other's limbs shifted left.
    let exponent = Swift.min(x.exponent, y.exponent)
    let a = x.limbsShifted(by: x.exponent - exponent)
    let b = y.limbsShifted(by: y.exponent - exponent)
    if x.negative == y.negative {
      return ExactDyadic(
        limbs: add(a, b), negative: x.negative, exponent: exponent)
    }
    if compare(a, b) >= 0 {
      return ExactDyadic(
        limbs: subtract(a, b), negative: x.negative, exponent: exponent)
    }
    return ExactDyadic(
      limbs: subtract(b, a), negative: y.negative, exponent: exponent)
  }

  package static func - (x: ExactDyadic, y: ExactDyadic) -> ExactDyadic {
    x + -y
  }

  /// |m|·2^bits as limbs.
  package func limbsShifted(by bits: Int) -> [UInt32] {
    guard bits > 0 else { return limbs }
    let (words, rest) = (bits / 32, bits % 32)
    var result = [UInt32](repeating: 0, count: words)
    var carry: UInt32 = 0
    for limb in limbs {
      result.append(rest == 0 ? limb : (limb << rest) | carry)
      carry = rest == 0 ? 0 : limb >> (32 - rest)
    }
    if carry != 0 { result.append(carry) }
    return result
  }

  package static func add(_ a: [UInt32], _ b: [UInt32]) -> [UInt32] {
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
  package static func subtract(_ a: [UInt32], _ b: [UInt32]) -> [UInt32] {
    var result: [UInt32] = []
    var borrow: Int64 = 0
    for index in 0..<a.count {
      var difference =
        Int64(a[index]) - Int64(index < b.count ? b[index] : 0) - borrow
      borrow = difference < 0 ? 1 : 0
      if difference < 0 { difference += 1 << 32 }
      result.append(UInt32(difference))
    }
    return result
  }

  package static func compare(_ a: [UInt32], _ b: [UInt32]) -> Int {
    let (a, b) = (trimmed(a), trimmed(b))
    if a.count != b.count { return a.count < b.count ? -1 : 1 }
    for index in stride(from: a.count - 1, through: 0, by: -1)
    where a[index] != b[index] {
      return a[index] < b[index] ? -1 : 1
    }
    return 0
  }

  package static func trimmed(_ a: [UInt32]) -> [UInt32] {
    var a = a
    while a.last == 0 { a.removeLast() }
    return a
  }

  /// The `count` ≤ 64 bits of |m| below bit `top` (exclusive), bits below
  /// 0 read as zeros.
  package func bits(below top: Int, count: Int) -> UInt64 {
    var result: UInt64 = 0
    for position in stride(from: top - 1, through: top - count, by: -1) {
      result <<= 1
      if position >= 0 {
        let limb = limbs[position / 32]
        result |= UInt64((limb >> UInt32(position % 32)) & 1)
      }
    }
    return result
  }
}

/// A DoubleDouble significand with an exponent of its own: m·2ᵉ, m in
/// [1, 2) or 0, so that the exact values' squares and products (beyond
/// Double's range at the extreme aspects) convert with 2⁻¹⁰⁴ relative
/// error and no overflow.
package struct ScaledDoubleDouble: CustomStringConvertible {
  package var significand: DoubleDouble
  package var exponent: Int

  package static let zero = ScaledDoubleDouble(significand: 0, exponent: 0)

  package init(significand: DoubleDouble, exponent: Int) {
    guard significand != 0, significand.isFinite else {
      self.significand = significand
      self.exponent = 0
      return
    }
    let shift = significand.exponent
    self.significand = significand * Self.power(-shift)
    self.exponent = exponent + shift
  }

  /// `value` to 2⁻¹⁵⁸ relative, then rounded to DoubleDouble.
  package init(_ value: ExactDyadic) {
    guard !value.isZero else {
      self = .zero
      return
    }
    let width = value.bitWidth
    // Three chunks of 53 bits, each an exact Double.
    var sum = DoubleDouble(0)
    for chunk in 0..<3 {
      let bits = value.bits(below: width - 53 * chunk, count: 53)
      sum = sum + DoubleDouble(Double(bits)) * Self.power(-52 - 53 * chunk)
    }
    self.init(
      significand: value.negative ? -sum : sum,
      exponent: width - 1 + value.exponent)
  }

  package init(_ value: DoubleDouble) {
    self.init(significand: value, exponent: 0)
  }

  package static func power(_ e: Int) -> DoubleDouble {
    DoubleDouble(Double(sign: .plus, exponent: e, significand: 1))
  }

  package var isZero: Bool { significand == 0 }

  package var description: String { "\(significand.hi)·2^\(exponent)" }

  /// The value as a DoubleDouble (0 or ∞ outside its range).
  package var value: DoubleDouble {
    guard !isZero else { return 0 }
    // In two steps, so that neither factor leaves Double's range first.
    let half = exponent / 2
    return significand * Self.power(half) * Self.power(exponent - half)
  }

  package var magnitude: ScaledDoubleDouble {
    ScaledDoubleDouble(significand: significand.magnitude, exponent: exponent)
  }

  package static func * (x: Self, y: Self) -> Self {
    Self(
      significand: x.significand * y.significand,
      exponent: x.exponent + y.exponent)
  }

  package static func / (x: Self, y: Self) -> Self {
    Self(
      significand: x.significand / y.significand,
      exponent: x.exponent - y.exponent)
  }

  package static func + (x: Self, y: Self) -> Self {
    if x.isZero { return y }
    if y.isZero { return x }
    let (large, small) = x.exponent >= y.exponent ? (x, y) : (y, x)
    let gap = large.exponent - small.exponent
    guard gap < 300 else { return large }
    return Self(
      significand: large.significand + small.significand * power(-gap),
      exponent: large.exponent)
  }

  package static prefix func - (x: Self) -> Self {
    Self(significand: -x.significand, exponent: x.exponent)
  }

  package static func - (x: Self, y: Self) -> Self { x + -y }

  package func squareRoot() -> Self {
    guard !isZero else { return self }
    let even = exponent.isMultiple(of: 2)
    let m = even ? significand : significand * 2
    let e = even ? exponent : exponent - 1
    return Self(significand: m.squareRoot(), exponent: e / 2)
  }

  package static func < (x: Self, y: Self) -> Bool { (x - y).significand < 0 }
}
