import Geometry

extension DoubleDoubleSignificand: FixedWidthInteger, UnsignedInteger {
  @usableFromInline
  package typealias IntegerLiteralType = UInt64
  @usableFromInline
  package typealias Magnitude = DoubleDoubleSignificand

  @inlinable
  package init(integerLiteral value: UInt64) {
    self.init(high: 0, low: value)
  }

  @inlinable
  package init(_truncatingBits bits: UInt) {
    self.init(high: 0, low: UInt64(bits))
  }

  @inlinable package static var bitWidth: Int { 128 }
  @inlinable package static var max: Self { Self(high: .max, low: .max) }
  @inlinable package static var min: Self { Self(high: 0, low: 0) }
  @inlinable package var magnitude: Self { self }

  /// The words, least significant first, without allocating: the standard
  /// library's conversions to other integers read them.
  @frozen
  @usableFromInline
  package struct Words: RandomAccessCollection, Sendable {
    @usableFromInline
    package let value: DoubleDoubleSignificand

    @inlinable
    package init(value: DoubleDoubleSignificand) { self.value = value }

    @inlinable package var startIndex: Int { 0 }
    @inlinable package var endIndex: Int { 128 / UInt.bitWidth }

    @inlinable
    package subscript(position: Int) -> UInt {
      precondition(position >= 0 && position < endIndex, "index out of range")
      let shifted = value.shiftedRight(position * UInt.bitWidth)
      return UInt(truncatingIfNeeded: shifted.low)
    }
  }

  @inlinable package var words: Words { Words(value: self) }

  @inlinable package var nonzeroBitCount: Int {
    high.nonzeroBitCount + low.nonzeroBitCount
  }
  @inlinable package var leadingZeroBitCount: Int {
    high == 0 ? 64 + low.leadingZeroBitCount : high.leadingZeroBitCount
  }
  @inlinable package var trailingZeroBitCount: Int {
    low == 0 ? 64 + high.trailingZeroBitCount : low.trailingZeroBitCount
  }
  @inlinable package var byteSwapped: Self {
    Self(high: low.byteSwapped, low: high.byteSwapped)
  }

  // MARK: Arithmetic reporting overflow

  @inlinable
  package func addingReportingOverflow(
    _ other: Self
  ) -> (partialValue: Self, overflow: Bool) {
    let (l, carry) = low.addingReportingOverflow(other.low)
    let (h1, o1) = high.addingReportingOverflow(other.high)
    let (h2, o2) = h1.addingReportingOverflow(carry ? 1 : 0)
    return (Self(high: h2, low: l), o1 || o2)
  }

  @inlinable
  package func subtractingReportingOverflow(
    _ other: Self
  ) -> (partialValue: Self, overflow: Bool) {
    let (l, borrow) = low.subtractingReportingOverflow(other.low)
    let (h1, o1) = high.subtractingReportingOverflow(other.high)
    let (h2, o2) = h1.subtractingReportingOverflow(borrow ? 1 : 0)
    return (Self(high: h2, low: l), o1 || o2)
  }

  @inlinable
  package func multipliedReportingOverflow(
    by other: Self
  ) -> (partialValue: Self, overflow: Bool) {
    let full = multipliedFullWidth(by: other)
    return (full.low, full.high != 0)
  }

  /// Schoolbook multiplication on 64-bit limbs.
  @inlinable
  package func multipliedFullWidth(by other: Self) -> (high: Self, low: Self) {
    let a = (low, high)
    let b = (other.low, other.high)
    // r0 + r1·2⁶⁴ + r2·2¹²⁸ + r3·2¹⁹²
    let p00 = a.0.multipliedFullWidth(by: b.0)
    let p01 = a.0.multipliedFullWidth(by: b.1)
    let p10 = a.1.multipliedFullWidth(by: b.0)
    let p11 = a.1.multipliedFullWidth(by: b.1)
    let r0 = p00.low
    var r1 = p00.high
    var r2 = p11.low
    var r3 = p11.high
    func add(_ value: UInt64, toR1: Bool) {
      // Adds value at limb 1 (or 2), carrying upward.
      if toR1 {
        let (s, c) = r1.addingReportingOverflow(value)
        r1 = s
        if c { add(1, toR1: false) }
      } else {
        let (s, c) = r2.addingReportingOverflow(value)
        r2 = s
        if c { r3 &+= 1 }
      }
    }
    add(p01.low, toR1: true)
    add(p10.low, toR1: true)
    add(p01.high, toR1: false)
    add(p10.high, toR1: false)
    return (Self(high: r3, low: r2), Self(high: r1, low: r0))
  }

  /// Bit-serial restoring division; the quotient must fit (dividend.high
  /// below `self`).
  @inlinable
  package func dividingFullWidth(
    _ dividend: (high: Self, low: Self)
  ) -> (quotient: Self, remainder: Self) {
    precondition(self != 0, "division by zero")
    precondition(dividend.high < self, "quotient overflows 128 bits")
    // Fast paths for what the standard library's conversions divide: by
    // a power of two, and within 64 bits.
    if dividend.high == 0 {
      if nonzeroBitCount == 1 {
        let mask = self.subtractingReportingOverflow(1).partialValue
        return (
          dividend.low.shiftedRight(trailingZeroBitCount),
          dividend.low & mask
        )
      }
      if high == 0 && dividend.low.high == 0 {
        let (q, r) = dividend.low.low.quotientAndRemainder(dividingBy: low)
        return (Self(high: 0, low: q), Self(high: 0, low: r))
      }
    }
    var remainder = dividend.high
    var rest = dividend.low
    var quotient: Self = 0
    for _ in 0..<128 {
      let carry = remainder.high >> 63
      remainder = remainder.shiftedLeft(1)
      remainder.low |= rest.high >> 63
      rest = rest.shiftedLeft(1)
      quotient = quotient.shiftedLeft(1)
      if carry != 0 || remainder >= self {
        remainder = remainder.subtractingReportingOverflow(self).partialValue
        quotient.low |= 1
      }
    }
    return (quotient, remainder)
  }

  @inlinable
  package func dividedReportingOverflow(
    by other: Self
  ) -> (partialValue: Self, overflow: Bool) {
    if other == 0 { return (self, true) }
    return (other.dividingFullWidth((0, self)).quotient, false)
  }

  @inlinable
  package func remainderReportingOverflow(
    dividingBy other: Self
  ) -> (partialValue: Self, overflow: Bool) {
    if other == 0 { return (self, true) }
    return (other.dividingFullWidth((0, self)).remainder, false)
  }

  // MARK: Operators

  @inlinable
  package static func + (lhs: Self, rhs: Self) -> Self {
    let result = lhs.addingReportingOverflow(rhs)
    precondition(!result.overflow, "arithmetic overflow")
    return result.partialValue
  }

  @inlinable
  package static func - (lhs: Self, rhs: Self) -> Self {
    let result = lhs.subtractingReportingOverflow(rhs)
    precondition(!result.overflow, "arithmetic overflow")
    return result.partialValue
  }

  @inlinable
  package static func * (lhs: Self, rhs: Self) -> Self {
    let result = lhs.multipliedReportingOverflow(by: rhs)
    precondition(!result.overflow, "arithmetic overflow")
    return result.partialValue
  }

  @inlinable
  package static func / (lhs: Self, rhs: Self) -> Self {
    precondition(rhs != 0, "division by zero")
    return lhs.dividedReportingOverflow(by: rhs).partialValue
  }

  @inlinable
  package static func % (lhs: Self, rhs: Self) -> Self {
    precondition(rhs != 0, "division by zero")
    return lhs.remainderReportingOverflow(dividingBy: rhs).partialValue
  }

  @inlinable package static func += (lhs: inout Self, rhs: Self) {
    lhs = lhs + rhs
  }
  @inlinable package static func -= (lhs: inout Self, rhs: Self) {
    lhs = lhs - rhs
  }
  @inlinable package static func *= (lhs: inout Self, rhs: Self) {
    lhs = lhs * rhs
  }
  @inlinable package static func /= (lhs: inout Self, rhs: Self) {
    lhs = lhs / rhs
  }
  @inlinable package static func %= (lhs: inout Self, rhs: Self) {
    lhs = lhs % rhs
  }

  @inlinable package static func &= (lhs: inout Self, rhs: Self) {
    lhs = Self(high: lhs.high & rhs.high, low: lhs.low & rhs.low)
  }
  @inlinable package static func |= (lhs: inout Self, rhs: Self) {
    lhs = Self(high: lhs.high | rhs.high, low: lhs.low | rhs.low)
  }
  @inlinable package static func ^= (lhs: inout Self, rhs: Self) {
    lhs = Self(high: lhs.high ^ rhs.high, low: lhs.low ^ rhs.low)
  }
  @inlinable package static prefix func ~ (x: Self) -> Self {
    Self(high: ~x.high, low: ~x.low)
  }

  /// Masking shifts: the count is taken modulo 128.
  @inlinable package static func &>> (lhs: Self, rhs: Self) -> Self {
    lhs.shiftedRight(Int(rhs.low & 127))
  }
  @inlinable package static func &<< (lhs: Self, rhs: Self) -> Self {
    lhs.shiftedLeft(Int(rhs.low & 127))
  }

  // Stated, or Strideable's default (by distance, which traps beyond Int)
  // would be chosen over the synthesised one.
  @inlinable
  package static func == (lhs: Self, rhs: Self) -> Bool {
    lhs.high == rhs.high && lhs.low == rhs.low
  }

  @inlinable
  package func hash(into hasher: inout Hasher) {
    hasher.combine(high)
    hasher.combine(low)
  }

  @inlinable
  package static func < (lhs: Self, rhs: Self) -> Bool {
    lhs.high != rhs.high ? lhs.high < rhs.high : lhs.low < rhs.low
  }
}
