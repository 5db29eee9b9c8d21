/// Decimal text to Double, fast for the short numbers scene files hold.
///
/// Numbers with at most 19 significant digits whose value is an integer below
/// 2^53 times or divided by an exact power of ten up to 10^22 are converted
/// with one correctly rounded multiplication or division (Clinger's fast
/// path), which covers every number `gen_spheres.py` writes; anything else
/// falls back to the standard library's correctly rounded conversion. Both
/// give the same, correctly rounded, result.
enum DecimalParser {
  private static let exactPowersOfTen: [Double] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
  ]

  static func parse(_ text: UnsafeBufferPointer<UInt8>) -> Double? {
    var index = 0
    let count = text.count
    guard count > 0 else { return nil }
    var negative = false
    if text[0] == UInt8(ascii: "-") || text[0] == UInt8(ascii: "+") {
      negative = text[0] == UInt8(ascii: "-")
      index = 1
    }
    var mantissa: UInt64 = 0
    var digits = 0
    var significantDigits = 0
    var exponent = 0
    while index < count, let digit = decimalDigit(text[index]) {
      accumulate(digit, &mantissa, &significantDigits, &exponent, fraction: false)
      digits += 1
      index += 1
    }
    if index < count && text[index] == UInt8(ascii: ".") {
      index += 1
      while index < count, let digit = decimalDigit(text[index]) {
        accumulate(digit, &mantissa, &significantDigits, &exponent, fraction: true)
        digits += 1
        index += 1
      }
    }
    if digits == 0 { return slowPath(text) }
    if index < count && (text[index] | 0x20) == UInt8(ascii: "e") {
      index += 1
      var exponentNegative = false
      if index < count
        && (text[index] == UInt8(ascii: "-") || text[index] == UInt8(ascii: "+"))
      {
        exponentNegative = text[index] == UInt8(ascii: "-")
        index += 1
      }
      var written = 0
      var exponentDigits = 0
      while index < count, let digit = decimalDigit(text[index]) {
        if written < 100_000 { written = written * 10 + Int(digit) }
        exponentDigits += 1
        index += 1
      }
      guard exponentDigits > 0 else { return nil }
      exponent += exponentNegative ? -written : written
    }
    guard index == count else { return nil }
    if significantDigits > 19 || mantissa > (1 << 53) || exponent < -22
      || exponent > 22
    {
      return slowPath(text)
    }
    var value = Double(mantissa)
    if exponent < 0 {
      value /= exactPowersOfTen[-exponent]
    } else {
      value *= exactPowersOfTen[exponent]
    }
    return negative ? -value : value
  }

  private static func decimalDigit(_ byte: UInt8) -> UInt64? {
    byte >= UInt8(ascii: "0") && byte <= UInt8(ascii: "9")
      ? UInt64(byte - UInt8(ascii: "0")) : nil
  }

  /// Leading zeros are not significant; digits past the 19th only mark the
  /// number for the slow path.
  private static func accumulate(
    _ digit: UInt64, _ mantissa: inout UInt64, _ significant: inout Int,
    _ exponent: inout Int, fraction: Bool
  ) {
    if mantissa == 0 && digit == 0 {
      if fraction { exponent -= 1 }
      return
    }
    significant += 1
    if significant <= 19 {
      mantissa = mantissa * 10 + digit
      if fraction { exponent -= 1 }
    } else if !fraction {
      exponent += 1
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
