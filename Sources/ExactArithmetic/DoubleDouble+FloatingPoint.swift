import Geometry

// DoubleDouble as a FloatingPoint: sign, exponent and significand in the
// 106-bit model, neighbours, classification and the arithmetic
// requirements (see DoubleDouble+BinaryFloatingPoint.swift for the format).

extension DoubleDouble {
  // MARK: Sign, exponent, significand

  @inlinable package var sign: FloatingPointSign { hi.sign }

  @inlinable package var magnitude: DoubleDouble {
    hi.sign == .minus ? -self : self
  }

  /// The exponent of the leading bit (Int.min for zero, Int.max for
  /// infinities and NaN, as Double).
  @inlinable
  package var exponent: Int {
    guard hi.isNormal else { return hi.exponent }
    if hi.significandBitPattern == 0 && lo != 0 && (lo < 0) != (hi < 0) {
      return hi.exponent - 1
    }
    return hi.exponent
  }

  /// In [1, 2) for finite non-zero values; as Double's for the others.
  @inlinable
  package var significand: DoubleDouble {
    guard hi.isFinite, hi != 0 else {
      return DoubleDouble(uncheckedHi: hi.significand, lo: 0)
    }
    let scale = -exponent
    let sameSign = (lo < 0) == (hi < 0)
    return DoubleDouble.normalized(
      Double(sign: .plus, exponent: scale, significand: hi.magnitude),
      Double(
        sign: sameSign ? .plus : .minus, exponent: scale,
        significand: lo.magnitude))
  }

  /// ±significand·2^exponent, rounded to the format.
  @inlinable
  package init(
    sign: FloatingPointSign, exponent: Int, significand: DoubleDouble
  ) {
    let hi = Double(sign: sign, exponent: exponent, significand: significand.hi)
    guard hi.isFinite, hi != 0 else {
      self.init(uncheckedHi: hi, lo: 0)
      return
    }
    let lo = Double(sign: sign, exponent: exponent, significand: significand.lo)
    self = Self.normalized(hi, lo)
  }

  @inlinable
  package init(signOf sign: DoubleDouble, magnitudeOf magnitude: DoubleDouble) {
    self = sign.sign == magnitude.sign ? magnitude : -magnitude
  }

  /// `value` = (odd or zero integer)·2^(exponent), for Double.
  @inlinable
  static func integerAndExponent(_ value: Double) -> (UInt64, Int) {
    let magnitude = value.magnitude
    let raw =
      magnitude.isNormal
      ? magnitude.significandBitPattern | 1 << 52
      : magnitude.significandBitPattern
    let unit = magnitude.isNormal ? Int(magnitude.exponent) - 52 : -1074
    let zeros = raw == 0 ? 0 : raw.trailingZeroBitCount
    return (raw >> zeros, unit + zeros)
  }

  @inlinable
  package var exponentBitPattern: UInt {
    if !hi.isFinite { return 2047 }
    if !hi.isNormal { return 0 }
    return UInt(exponent + 1023)
  }

  /// The 105 fraction bits below the leading one (all bits for subnormals,
  /// whose unit is 2⁻¹¹²⁷); for NaN, Double's payload shifted to the top.
  @inlinable
  package var significandBitPattern: DoubleDoubleSignificand {
    if hi.isNaN {
      return DoubleDoubleSignificand(high: 0, low: hi.significandBitPattern)
        .shiftedLeft(53)
    }
    guard hi.isFinite, hi != 0 else { return 0 }
    let unit = hi.isNormal ? exponent - 105 : -1127
    let (hiInteger, hiExponent) = Self.integerAndExponent(hi)
    var pattern = DoubleDoubleSignificand(high: 0, low: hiInteger)
      .shiftedLeft(hiExponent - unit)
    if lo != 0 {
      let (loInteger, loExponent) = Self.integerAndExponent(lo)
      let tail = DoubleDoubleSignificand(high: 0, low: loInteger)
        .shiftedLeft(loExponent - unit)
      pattern = (lo < 0) == (hi < 0) ? pattern + tail : pattern - tail
    }
    return hi.isNormal ? pattern & Self.fractionMask : pattern
  }

  /// The value those fields encode, rounded to the nearest pair where the
  /// format holds more than a pair can (see the type's comment); a NaN
  /// keeps the payload's top 52 bits.
  @inlinable
  package init(
    sign: FloatingPointSign, exponentBitPattern: UInt,
    significandBitPattern: DoubleDoubleSignificand
  ) {
    let fraction = significandBitPattern & Self.fractionMask
    if exponentBitPattern >= 2047 {
      if fraction == 0 {
        self.init(uncheckedHi: sign == .minus ? -.infinity : .infinity, lo: 0)
        return
      }
      let payload = fraction.shiftedRight(53).low
      self.init(
        uncheckedHi: Double(
          sign: sign, exponentBitPattern: 2047,
          significandBitPattern: payload == 0 ? 1 : payload),
        lo: 0)
      return
    }
    let integer =
      exponentBitPattern == 0
      ? fraction : fraction | DoubleDoubleSignificand(high: 1 << 41, low: 0)
    let unit =
      exponentBitPattern == 0 ? -1127 : Int(exponentBitPattern) - 1023 - 105
    guard integer != 0 else {
      self.init(uncheckedHi: sign == .minus ? -0.0 : 0.0, lo: 0)
      return
    }
    // hi: the top 53 bits rounded to nearest even; lo: the signed rest,
    // at most 53 bits. Both exact as Doubles before scaling.
    let width = 128 - integer.leadingZeroBitCount
    let shift = Swift.max(width - 53, 0)
    var top = integer.shiftedRight(shift)
    if shift > 0 {
      let rest = integer - top.shiftedLeft(shift)
      let half = DoubleDoubleSignificand(high: 0, low: 1).shiftedLeft(shift - 1)
      if rest > half || (rest == half && top.low & 1 == 1) { top += 1 }
    }
    let rounded = top.shiftedLeft(shift)
    let tailIsNegative = rounded > integer
    let tail = tailIsNegative ? rounded - integer : integer - rounded
    let hi = Double(
      sign: sign, exponent: unit + shift, significand: Double(top.low))
    let lo = Double(
      sign: tailIsNegative == (sign == .minus) ? .plus : .minus,
      exponent: unit, significand: Double(tail.low))
    guard hi.isFinite else {
      self.init(uncheckedHi: hi, lo: 0)
      return
    }
    self = Self.normalized(hi, lo)
  }

  /// 2^exponent with the value's sign; Double's for zeros and non-finite.
  @inlinable
  package var binade: DoubleDouble {
    guard hi.isFinite, hi != 0 else {
      return DoubleDouble(uncheckedHi: hi.binade, lo: 0)
    }
    return DoubleDouble(
      uncheckedHi: Double(sign: sign, exponent: exponent, significand: 1),
      lo: 0)
  }

  /// Bits after the leading one up to the last set bit; −1 for zeros and
  /// non-finite values, as Double.
  @inlinable
  package var significandWidth: Int {
    guard hi.isFinite, hi != 0 else { return -1 }
    let last = lo != 0 ? lo : hi
    return exponent - (Int(last.exponent) - last.significandWidth)
  }

  // MARK: Neighbours

  /// The spacing of values at `self`: 2^(exponent − 105), never below
  /// 2⁻¹⁰⁷⁴ (see the type's comment); NaN for non-finite values.
  @inlinable
  package var ulp: DoubleDouble {
    guard hi.isFinite else { return .nan }
    guard hi != 0 else { return .leastNonzeroMagnitude }
    return DoubleDouble(
      uncheckedHi: Double(
        sign: .plus, exponent: Swift.max(exponent - 105, -1074),
        significand: 1),
      lo: 0)
  }

  /// The next value towards zero from a finite positive one.
  @inlinable
  var positiveNextDown: DoubleDouble {
    var unit = exponent - 105
    if significandWidth == 0 { unit -= 1 }
    let step = Double(
      sign: .plus, exponent: Swift.max(unit, -1074), significand: 1)
    // lo − step is exact: lo is a multiple of step within 2⁵² of them.
    return DoubleDouble.normalized(hi, lo - step)
  }

  @inlinable
  package var nextUp: DoubleDouble {
    if hi.isNaN { return DoubleDouble(uncheckedHi: hi + 0, lo: 0) }
    if hi == -.infinity { return -.greatestFiniteMagnitude }
    if hi == .infinity { return self }
    if hi == 0 { return .leastNonzeroMagnitude }
    if hi < 0 {
      let down = (-self).positiveNextDown
      return down.hi == 0 ? DoubleDouble(uncheckedHi: -0.0, lo: 0) : -down
    }
    return DoubleDouble.normalized(hi, lo + ulp.hi)
  }

  // MARK: Classification

  @inlinable package var isNormal: Bool { hi.isNormal }
  @inlinable package var isFinite: Bool { hi.isFinite }
  @inlinable package var isZero: Bool { hi == 0 }
  @inlinable package var isSubnormal: Bool { hi.isSubnormal }
  @inlinable package var isInfinite: Bool { hi.isInfinite }
  @inlinable package var isNaN: Bool { hi.isNaN }
  @inlinable package var isSignalingNaN: Bool { hi.isSignalingNaN }
  @inlinable package var isCanonical: Bool { true }

  @inlinable package func isEqual(to other: DoubleDouble) -> Bool {
    self == other
  }
  @inlinable package func isLess(than other: DoubleDouble) -> Bool {
    self < other
  }
  @inlinable package func isLessThanOrEqualTo(_ other: DoubleDouble) -> Bool {
    self < other || self == other
  }

  // MARK: Arithmetic requirements

  @inlinable package mutating func negate() { self = -self }

  @inlinable package static func += (x: inout DoubleDouble, y: DoubleDouble) {
    x = x + y
  }
  @inlinable package static func -= (x: inout DoubleDouble, y: DoubleDouble) {
    x = x - y
  }
  @inlinable package static func *= (x: inout DoubleDouble, y: DoubleDouble) {
    x = x * y
  }
  @inlinable package static func /= (x: inout DoubleDouble, y: DoubleDouble) {
    x = x / y
  }

  @inlinable package mutating func formSquareRoot() { self = squareRoot() }

  /// self + lhs·rhs, not fused: the product is rounded (≤ 5u²), then the
  /// sum (≤ 4u² + 13u³).
  @inlinable
  package mutating func addProduct(_ lhs: DoubleDouble, _ rhs: DoubleDouble) {
    self = self + lhs * rhs
  }

  /// |self| reduced by multiples 2^k·|divisor| from the largest k down:
  /// each subtraction is between values within a factor 2 of each other,
  /// so its exact result fits 106 bits; the quotient's last bit comes too.
  @inlinable
  func reduced(by divisor: DoubleDouble) -> (DoubleDouble, quotientIsOdd: Bool)
  {
    var rest = magnitude
    var isOdd = false
    while rest >= divisor {
      var k = rest.exponent - divisor.exponent
      var shifted = DoubleDouble(
        sign: .plus, exponent: k, significand: divisor)
      if shifted > rest {
        k -= 1
        shifted = DoubleDouble(sign: .plus, exponent: k, significand: divisor)
      }
      rest = rest - shifted
      isOdd = k == 0
    }
    return (rest, isOdd)
  }

  /// self − q·other with q = self/other truncated (fmod).
  @inlinable
  package mutating func formTruncatingRemainder(
    dividingBy other: DoubleDouble
  ) {
    guard isFinite, !other.isNaN, other != 0 else {
      self = .nan
      return
    }
    guard other.isFinite else { return }
    let (rest, _) = reduced(by: other.magnitude)
    self = DoubleDouble(signOf: self, magnitudeOf: rest)
  }

  /// IEEE remainder: self − q·other with q = self/other rounded to nearest
  /// even, so |result| ≤ |other|/2.
  @inlinable
  package mutating func formRemainder(dividingBy other: DoubleDouble) {
    guard isFinite, !other.isNaN, other != 0 else {
      self = .nan
      return
    }
    guard other.isFinite else { return }
    let divisor = other.magnitude
    var (rest, isOdd) = reduced(by: divisor)
    let half = DoubleDouble(sign: .plus, exponent: -1, significand: divisor)
    if rest > half || (rest == half && isOdd) {
      rest = rest - divisor
    }
    self = sign == .minus ? -rest : rest
    if rest == 0 { self = DoubleDouble(signOf: self, magnitudeOf: 0) }
  }

  /// Rounded to an integer by `rule`, exactly.
  @inlinable
  package mutating func round(_ rule: FloatingPointRoundingRule) {
    guard hi.isFinite, hi != 0 else { return }
    // self = floor + fraction, fraction in [0, 1) classified against ½;
    // when hi is not an integer, |lo| < hi's distance to any integer.
    let floor: DoubleDouble
    let fractionHalf: Double  // exact fraction part of hi or lo
    let tieBreak: Double  // lo, when hi's fraction decides
    let hiFloor = hi.rounded(.down)
    if hiFloor != hi {
      floor = DoubleDouble(hiFloor)
      fractionHalf = hi - hiFloor
      tieBreak = lo
    } else {
      let loFloor = lo.rounded(.down)
      floor = DoubleDouble(hi, loFloor)
      fractionHalf = lo - loFloor
      tieBreak = 0
    }
    let isInteger = fractionHalf == 0 && tieBreak == 0
    if isInteger { return }
    let comparison: Int  // sign of fraction − ½
    if fractionHalf != 0.5 {
      comparison = fractionHalf < 0.5 ? -1 : 1
    } else {
      comparison = tieBreak == 0 ? 0 : (tieBreak < 0 ? -1 : 1)
    }
    let up: Bool
    switch rule {
    case .down: up = false
    case .up: up = true
    case .towardZero: up = hi < 0
    case .awayFromZero: up = hi > 0
    case .toNearestOrEven:
      if comparison == 0 {
        let half = DoubleDouble(sign: .plus, exponent: -1, significand: floor)
        up = half.rounded(.down) != half
      } else {
        up = comparison > 0
      }
    case .toNearestOrAwayFromZero:
      up = comparison == 0 ? hi > 0 : comparison > 0
    @unknown default:
      up = comparison > 0
    }
    let result = up ? floor + 1 : floor
    // An integer result of zero keeps the sign of the value rounded.
    self = result == 0 ? DoubleDouble(signOf: self, magnitudeOf: 0) : result
  }
}
