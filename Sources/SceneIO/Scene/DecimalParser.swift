import Geometry
import SceneDescription
import PlatformSupport

/// Decimal text to Double, fast for the short numbers scene files hold.
///
/// Numbers with at most 19 significant digits whose value is an integer below
/// 2^53 times or divided by an exact power of ten up to 10^22 are converted
/// with one correctly rounded multiplication or division (Clinger's fast
/// path), which covers every number `gen_spheres.py` writes; anything else
/// falls back to the standard library's correctly rounded conversion. Both
/// give the same, correctly rounded, result.
///
/// Why the fast path is correctly rounded: the digits, leading zeros and
/// point removed, are an integer m ≤ 2^53, and every such integer is a
/// Double exactly, so `Double(m)` rounds nothing. Every 10^k with k ≤ 22 is
/// one too: 10^k = 2^k · 5^k and 5^22 < 2^53, so its odd part fits in the
/// significand. The number's value is m · 10^e or m / 10^−e, one IEEE
/// multiplication or division of two exact operands, which IEEE 754 rounds
/// correctly (to nearest, ties to even) by definition. The product is at
/// most 2^53 · 10^22 < 10^39 and a quotient of nonzero m at least
/// 1 / 10^22: neither overflows nor lands among the subnormals, where a
/// second rounding could occur.
enum DecimalParser {
  private static let exactPowersOfTen: [Double] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
  ]

  /// How the longest prefix of a text that reads as a decimal number
  /// reads: `[+-]digits[.digits][(e|E)[+-]digits]`, digits on at least one
  /// side of the point.
  enum Prefix {
    /// Converted by the fast path; the number ends before `end`.
    case fast(Double, end: UnsafePointer<UInt8>)
    /// A number the fast path leaves to the standard library.
    case slow(end: UnsafePointer<UInt8>)
    /// No digit before where an exponent could start: not a decimal number,
    /// though it may be `inf` or `nan`.
    case noDigits
    /// An exponent marker without digits after it.
    case invalid
  }

  static func parse(_ text: UnsafeBufferPointer<UInt8>) -> Double? {
    guard let start = text.baseAddress, !text.isEmpty else { return nil }
    let end = start + text.count
    switch prefix(from: start, to: end) {
    case .fast(let value, let stop): return stop == end ? value : nil
    case .slow(let stop): return stop == end ? slowPath(text) : nil
    case .noDigits: return slowPath(text)
    case .invalid: return nil
    }
  }

  /// Reads from `start` up to the first byte that cannot continue a number,
  /// never past `end`, which must not be `start`. One pass over raw bytes:
  /// the scene tokenizer converts the numbers of a sphere as it finds them
  /// with it, and `parse` checks that the number fills its text.
  static func prefix(
    from start: UnsafePointer<UInt8>, to end: UnsafePointer<UInt8>
  ) -> Prefix {
    var cursor = start
    let first = cursor.pointee
    let negative = first == UInt8(ascii: "-")
    if negative || first == UInt8(ascii: "+") { cursor += 1 }
    let digitsStart = cursor
    var (mantissa, exponent, digits) = allDigits(&cursor, end)
    var significantDigits = digits
    if digits > 19 {
      cursor = digitsStart
      (mantissa, exponent, significantDigits) = significantDigitsOnly(
        &cursor, end)
    }
    if digits == 0 { return .noDigits }
    if cursor < end && (cursor.pointee | 0x20) == UInt8(ascii: "e") {
      cursor += 1
      var exponentNegative = false
      if cursor < end
        && (cursor.pointee == UInt8(ascii: "-")
          || cursor.pointee == UInt8(ascii: "+"))
      {
        exponentNegative = cursor.pointee == UInt8(ascii: "-")
        cursor += 1
      }
      var written = 0
      var exponentDigits = 0
      while cursor < end, let digit = decimalDigit(cursor.pointee) {
        // Past 100,000 the value is 0 or infinite whatever the digits:
        // the slow path decides, and `written` cannot overflow.
        if written < 100_000 { written = written &* 10 &+ Int(digit) }
        exponentDigits &+= 1
        cursor += 1
      }
      guard exponentDigits > 0 else { return .invalid }
      exponent += exponentNegative ? -written : written
    }
    if significantDigits > 19 || mantissa > (1 << 53) || exponent < -22
      || exponent > 22
    {
      return .slow(end: cursor)
    }
    var value = Double(mantissa)
    if exponent < 0 {
      value /= exactPowersOfTen[-exponent]
    } else {
      value *= exactPowersOfTen[exponent]
    }
    return .fast(negative ? -value : value, end: cursor)
  }

  private static func decimalDigit(_ byte: UInt8) -> UInt64? {
    let digit = byte &- UInt8(ascii: "0")
    return digit < 10 ? UInt64(digit) : nil
  }

  /// Reads `digits[.digits]`, every digit into the mantissa: leading
  /// zeros add nothing to it, so up to 19 digits in all (10^19 < 2^64) it
  /// is exactly the number's digits, as `significantDigitsOnly` reads
  /// them, and the exponent theirs too: −1 for each digit after the point.
  /// The mantissa of more digits is meaningless.
  private static func allDigits(
    _ cursor: inout UnsafePointer<UInt8>, _ end: UnsafePointer<UInt8>
  ) -> (mantissa: UInt64, exponent: Int, digits: Int) {
    var mantissa: UInt64 = 0
    let integerStart = cursor
    while cursor < end, let digit = decimalDigit(cursor.pointee) {
      mantissa = mantissa &* 10 &+ digit
      cursor += 1
    }
    let integerDigits = cursor - integerStart
    var fractionDigits = 0
    if cursor < end && cursor.pointee == UInt8(ascii: ".") {
      cursor += 1
      let fractionStart = cursor
      while cursor < end, let digit = decimalDigit(cursor.pointee) {
        mantissa = mantissa &* 10 &+ digit
        cursor += 1
      }
      fractionDigits = cursor - fractionStart
    }
    return (mantissa, -fractionDigits, integerDigits + fractionDigits)
  }

  /// Reads `digits[.digits]` for numbers of more than 19 digits: leading
  /// zeros are skipped, and digits past the 19th significant one only
  /// counted, to send the number to the slow path.
  private static func significantDigitsOnly(
    _ cursor: inout UnsafePointer<UInt8>, _ end: UnsafePointer<UInt8>
  ) -> (mantissa: UInt64, exponent: Int, significantDigits: Int) {
    var mantissa: UInt64 = 0
    var significantDigits = 0
    var exponent = 0
    while cursor < end, let digit = decimalDigit(cursor.pointee) {
      accumulate(
        digit, &mantissa, &significantDigits, &exponent, fraction: false)
      cursor += 1
    }
    if cursor < end && cursor.pointee == UInt8(ascii: ".") {
      cursor += 1
      while cursor < end, let digit = decimalDigit(cursor.pointee) {
        accumulate(
          digit, &mantissa, &significantDigits, &exponent, fraction: true)
        cursor += 1
      }
    }
    return (mantissa, exponent, significantDigits)
  }

  /// Leading zeros are not significant; digits past the 19th only mark the
  /// number for the slow path.
  private static func accumulate(
    _ digit: UInt64, _ mantissa: inout UInt64, _ significant: inout Int,
    _ exponent: inout Int, fraction: Bool
  ) {
    // Wrapping arithmetic, as none of it can overflow: 19 digits are
    // below 10^19 < 2^64, and the counts are bounded by the text's length.
    if mantissa == 0 && digit == 0 {
      if fraction { exponent &-= 1 }
      return
    }
    significant &+= 1
    if significant <= 19 {
      mantissa = mantissa &* 10 &+ digit
      if fraction { exponent &-= 1 }
    } else if !fraction {
      exponent &+= 1
    }
  }

  /// Also where `inf` and `nan` are recognised, so that they can be reported
  /// as non-finite rather than as not-a-number-at-all.
  private static func slowPath(_ text: UnsafeBufferPointer<UInt8>) -> Double? {
    // The standard library reads a C string, which would end at a NUL
    // byte and accept "inf\0junk" as infinity.
    guard !text.contains(0) else { return nil }
    return Double(String(decoding: text, as: UTF8.self))
  }
}
