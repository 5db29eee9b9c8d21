import Geometry

// DoubleDouble as a BinaryFloatingPoint: the 106-bit model of the type's
// comment, with Double's exponent range and encoding (bias 1023, exponent
// pattern 0 for zeros and subnormals, 2047 for infinities and NaNs) and 105
// fraction bits in a 128-bit raw significand.

extension DoubleDouble: BinaryFloatingPoint {
  @usableFromInline
  package typealias RawSignificand = DoubleDoubleSignificand
  @usableFromInline
  package typealias RawExponent = UInt
  @usableFromInline
  package typealias Exponent = Int
  @usableFromInline
  package typealias Magnitude = DoubleDouble
  @usableFromInline
  package typealias Stride = DoubleDouble
  /// Double: a literal means the Double it spells (see the type's comment).
  @usableFromInline
  package typealias FloatLiteralType = Double
  @usableFromInline
  package typealias IntegerLiteralType = Int64

  @inlinable
  package init(floatLiteral value: Double) { self.init(value) }

  @inlinable
  package init(integerLiteral value: Int64) { self.init(value) }

  // MARK: The format

  @inlinable package static var exponentBitCount: Int { 11 }
  /// 105 fraction bits: 106 significant bits, the most any normalised pair
  /// holds for every value of a binade (see the type's comment).
  @inlinable package static var significandBitCount: Int { 105 }

  /// The 105 fraction bits' mask.
  @inlinable static var fractionMask: DoubleDoubleSignificand {
    DoubleDoubleSignificand(high: (1 << 41) - 1, low: .max)
  }

  @inlinable package static var nan: DoubleDouble {
    DoubleDouble(uncheckedHi: .nan, lo: 0)
  }
  @inlinable package static var signalingNaN: DoubleDouble {
    DoubleDouble(uncheckedHi: .signalingNaN, lo: 0)
  }
  @inlinable package static var infinity: DoubleDouble {
    DoubleDouble(uncheckedHi: .infinity, lo: 0)
  }
  /// 2¹⁰²⁴ − 2⁹⁷⁰ − 2⁹¹⁸: the largest pair whose `hi` does not round to
  /// infinity, short of the format's 2¹⁰²⁴ − 2⁹¹⁸ (see the type's comment).
  @inlinable package static var greatestFiniteMagnitude: DoubleDouble {
    DoubleDouble(
      uncheckedHi: .greatestFiniteMagnitude, lo: 0x1.ffff_ffff_ffff_ep969)
  }
  /// 2⁻¹⁰²², Double's: below it `hi` is subnormal and `lo` zero.
  @inlinable package static var leastNormalMagnitude: DoubleDouble {
    DoubleDouble(uncheckedHi: .leastNormalMagnitude, lo: 0)
  }
  /// 2⁻¹⁰⁷⁴, Double's: the format's own subnormals below it cannot be held.
  @inlinable package static var leastNonzeroMagnitude: DoubleDouble {
    DoubleDouble(uncheckedHi: .leastNonzeroMagnitude, lo: 0)
  }
  /// π rounded toward zero to 106 bits, as FloatingPoint asks.
  @inlinable package static var pi: DoubleDouble {
    DoubleDouble(
      uncheckedHi: 0x1.921f_b544_42d1_8p1, lo: 0x1.1a62_6331_45c0_6p-53)
  }
  /// 2⁻¹⁰⁵.
  @inlinable package static var ulpOfOne: DoubleDouble {
    DoubleDouble(uncheckedHi: 0x1p-105, lo: 0)
  }

  // MARK: Conversions

  @inlinable
  package init(_ value: Float) { self.init(Double(value)) }

  #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
    /// Exact within Double's exponent range (64 bits fit in 106); outside
    /// it overflows to infinity or loses the bits below 2⁻¹⁰⁷⁴.
    @inlinable
    package init(_ value: Float80) {
      let hi = Double(value)
      guard hi.isFinite, hi != 0 else {
        self.init(uncheckedHi: hi, lo: 0)
        return
      }
      // value − hi is exact in Float80 (Sterbenz) and has at most 12 bits.
      self = Self.normalized(hi, Double(value - Float80(hi)))
    }
  #endif

  /// Exact from Float, Double, Float80 and DoubleDouble; other sources are
  /// split into three Doubles (each remainder exact in the source's own
  /// format), then rounded to 106 bits.
  @inlinable
  package init<Source: BinaryFloatingPoint>(_ value: Source) {
    if let value = value as? DoubleDouble {
      self = value
    } else if let value = value as? Double {
      self.init(value)
    } else if let value = value as? Float {
      self.init(Double(value))
    } else {
      #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
        if let value = value as? Float80 {
          self.init(value)
          return
        }
      #endif
      let hi = Double(value)
      guard hi.isFinite, hi != 0 else {
        self.init(uncheckedHi: hi, lo: 0)
        return
      }
      let rest = value - Source(hi)
      let mid = Double(rest)
      let low = Double(rest - Source(mid))
      self = Self.renormalized(hi, mid, low)
    }
  }

  /// nil unless `value` converts and converts back unchanged (NaN: nil).
  @inlinable
  package init?<Source: BinaryFloatingPoint>(exactly value: Source) {
    self.init(value)
    guard !value.isNaN, Source(self) == value else { return nil }
  }

  /// Exact for integers of at most 106 significant bits, otherwise rounded
  /// to nearest even; beyond the range, infinity.
  @inlinable
  package init<Source: BinaryInteger>(_ value: Source) {
    let magnitude = value.magnitude
    let width = Self.significantBitCount(magnitude)
    let result: DoubleDouble
    if width <= 53 {
      result = DoubleDouble(Double(magnitude))
    } else {
      // The top 106 bits, rounded to nearest even by the rest.
      let shift = Swift.max(width - 106, 0)
      var top = magnitude >> shift
      if shift > 0 {
        let rest = magnitude - (top << shift)
        let half = (1 as Source.Magnitude) << (shift - 1)
        if rest > half || (rest == half && top & 1 == 1) { top += 1 }
      }
      // top ≤ 2¹⁰⁶: both halves are exact in Double.
      let upper = Double(top >> 53) * 0x1p53
      let lower = Double(top & (((1 as Source.Magnitude) << 53) - 1))
      result = DoubleDouble(
        sign: .plus, exponent: shift, significand: DoubleDouble(upper, lower))
    }
    self = value < 0 ? -result : result
  }

  /// The position of the highest set bit plus one; 0 for zero.
  @inlinable
  static func significantBitCount<Magnitude: BinaryInteger>(
    _ magnitude: Magnitude
  ) -> Int {
    var count = 0
    for (index, word) in magnitude.words.enumerated() where word != 0 {
      count = index * UInt.bitWidth + UInt.bitWidth - word.leadingZeroBitCount
    }
    return count
  }

  @inlinable
  package func distance(to other: DoubleDouble) -> DoubleDouble {
    other - self
  }

  @inlinable
  package func advanced(by amount: DoubleDouble) -> DoubleDouble {
    self + amount
  }

  @inlinable
  package init(_ value: Int) {
    self.init(Int64(value))
  }

  /// nil unless `value` has at most 106 significant bits (and is in range).
  @inlinable
  package init?<Source: BinaryInteger>(exactly value: Source) {
    let magnitude = value.magnitude
    let width = Self.significantBitCount(magnitude)
    guard width - magnitude.trailingZeroBitCount <= 106 || width == 0 else {
      return nil
    }
    self.init(value)
    guard isFinite else { return nil }
  }
}
