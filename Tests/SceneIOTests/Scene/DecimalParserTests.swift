import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

final class DecimalParserTests: XCTestCase {
  func decimal(_ text: String) -> Double? {
    Array(text.utf8).withUnsafeBufferPointer { DecimalParser.parse($0) }
  }

  /// The parser and the standard library agree bit for bit (NaNs
  /// included), or both reject the text.
  func assertAgrees(
    _ text: String, _ context: @autoclosure () -> String = "",
    file: StaticString = #filePath, line: UInt = #line
  ) {
    let got = decimal(text)
    let want = Double(text)
    XCTAssertEqual(
      got?.bitPattern, want?.bitPattern,
      "\(text.debugDescription): \(got.map { "\($0)" } ?? "nil") vs "
        + "\(want.map { "\($0)" } ?? "nil") \(context())",
      file: file, line: line)
  }

  func testParse_Integers() {
    for text in [
      "0", "1", "7", "10", "123", "4096", "65535", "1000000",
      "9007199254740991",  // 2^53 − 1
      "9007199254740992",  // 2^53: the largest mantissa of the fast path
      "9007199254740993",  // 2^53 + 1: not a Double, rounds to even
      "9007199254740995",
      "18446744073709551615",  // 2^64 − 1, 20 digits
      "18446744073709551616",
      "123456789012345678901234567890",
    ] {
      assertAgrees(text)
    }
  }

  func testParse_Fractions() {
    for text in [
      "0.1", "0.2", "0.3", "0.5", ".5", "1.", "1.0", "3.14159",
      "2.718281828459045",
      "0.000001", "123.456", "0.1000000000000000055511151231257827",
      "1.00000000000000011102230246251565404236316680908203125",  // halfway
      "1.00000000000000011102230246251565404236316680908203124",
      "1.00000000000000011102230246251565404236316680908203126",
      "0.30000000000000004", "99.99", "1.5", "2.5",
    ] {
      assertAgrees(text)
    }
  }

  func testParse_Exponents() {
    for text in [
      "1e0", "1e1", "1e22", "1e23", "1e-22", "1e-23", "1E5", "1e+5", "1e-5",
      "2.5e-3",
      "123456789e22",  // mantissa below 2^53, exponent 22: the fast path's edge
      "9007199254740992e22", "9007199254740993e22", "1e-0",
      "1e00000000000000000001",
      "25e-1", "0.5e1", "5e-1", "4.35e-17", "7e-22", "1.7976931348623157e308",
      "1.7976931348623158e308",  // rounds down to the largest finite Double
      "1.7976931348623159e308",  // overflows to infinity
      "1e308", "1e309", "1e999", "1e100000", "1e99999999999999999999",
      "0e999", "0e99999999999", "1e-400", "1e-99999999999",
    ] {
      assertAgrees(text)
    }
  }

  func testParse_Subnormals() {
    for text in [
      "4.9406564584124654e-324", "5e-324", "4e-324", "3e-324",
      "2.4703282292062327e-324",  // just below half the least subnormal: 0
      "2.4703282292062328e-324",  // just above: the least subnormal
      "2.2250738585072011e-308",  // the largest subnormal's neighbourhood
      "2.2250738585072012e-308", "2.2250738585072014e-308", "1e-310", "1e-320",
    ] {
      assertAgrees(text)
    }
  }

  func testParse_LeadingZerosAndManyDigits() {
    for text in [
      "000123", "0000.0001", "00000000000000000000000001",
      "0.00000000000000000000000001",
      "000000000000000000000000000000.5", "1234567890123456789",
      "12345678901234567890",
      "0.12345678901234567890123", "9999999999999999999",
      "99999999999999999999e-20",
      "1000000000000000000000000", "1.0000000000000000000000001",
      "100000000000000000000000000000000000000e-38",
      "0.000000000000000000000000000001e30",
      "123456789012345678.9", "1234567890123456789.0",
      "0.1234567890123456789e19",
    ] {
      assertAgrees(text)
    }
  }

  func testParse_Signs() {
    for text in [
      "-0", "+0", "-0.0", "-0e10", "-1", "+1", "-.5", "+.5", "-1.", "-1e-400",
      "-1e400",
    ] {
      assertAgrees(text)
    }
    XCTAssertEqual(decimal("-0")?.sign, .minus)
    XCTAssertEqual(decimal("-0e10")?.sign, .minus)
  }

  /// Infinities and NaNs are recognised (through the standard library), so
  /// that the scene parser can call them non-finite rather than not numbers.
  func testParse_NonFiniteWords() {
    for text in [
      "inf", "-inf", "+inf", "infinity", "INF", "nan", "-nan", "NaN", "nan(12)",
    ] {
      assertAgrees(text)
      XCTAssertFalse(decimal(text)?.isFinite ?? true, text)
    }
  }

  func testParse_Invalid() {
    for text in [
      "", "-", "+", ".", "-.", "e5", "E5", "1e", "1e+", "1e-", "1.2.3", "1..2",
      "--1", "+-1",
      "1-", "1+", "1e5.5", "1e5e5", "abc", "1a", "a1", "1 ", " 1", "1_000",
      "1,5", "١",
      "∞", ".e1", "e", "in", "infx", "1f", "0b1",
    ] {
      XCTAssertNil(decimal(text), text.debugDescription)
      assertAgrees(text)
    }
  }

  /// A NUL byte is not part of any number. (`Double(String)` reads its
  /// argument as a C string and stops at the NUL, accepting "1\0" as 1, so
  /// it is no reference here.) Scene tokens can hold NULs: they end only at
  /// blanks, braces and `#`.
  func testParse_EmbeddedNULIsNotANumber() {
    for text in [
      "1\u{0}", "\u{0}", "\u{0}1", "1.5\u{0}e3", "inf\u{0}", "nan\u{0}x",
      "-inf\u{0}1",
    ] {
      XCTAssertNil(decimal(text), text.debugDescription)
    }
  }

  /// Hexadecimal literals, which `Double(String)` accepts, are not
  /// decimal numbers: refused, as a scene file should not contain them.
  func testParse_HexadecimalRefused() {
    for text in ["0x10", "0x1p3", "-0x1.8p1", "0X1F"] {
      XCTAssertNil(decimal(text), text)
      XCTAssertNotNil(Double(text), "\(text): the standard library accepts it")
    }
  }

  /// 100,000 values, each printed as %.17g (round trip), %.7g (scene-file
  /// precision) and Swift's shortest form, compared bit for bit with the
  /// standard library's correctly rounded parse. Half are random bit
  /// patterns (every binade, subnormals included: mostly the slow path),
  /// half are scene-sized, log-uniform in [1e−8, 1e8] (mostly the fast
  /// path, and its edges where %.17g gives 17 digits).
  func testParse_RandomFormattedValues() {
    forEachSeed(Self.seedCount(100_000), base: 0xDEC1_0001) { generator, seed in
      var value: Double
      if Bool.random(using: &generator) {
        value = Double(bitPattern: generator.next())
        if !value.isFinite { value = Double(generator.next() >> 11) }
      } else {
        value = generator.sign() * generator.logUniform(1e-8, 1e8)
      }
      for text in [
        String(format: "%.17g", value), String(format: "%.7g", value),
        "\(value)",
      ] {
        assertAgrees(text, "seed \(seed)")
      }
    }
  }

  /// 100,000 random decimal strings: up to 22 digits with or without a
  /// point, a sign, and an exponent in [−30, 30], around the fast path's
  /// limits (19 digits, 2^53, 10^±22).
  func testParse_RandomDecimalStrings() {
    forEachSeed(Self.seedCount(100_000), base: 0xDEC1_0002) { generator, seed in
      let count = Int.random(in: 1...22, using: &generator)
      var digits = (0..<count).map { _ in
        String(Int.random(in: 0...9, using: &generator))
      }.joined()
      if Bool.random(using: &generator) {
        let point = digits.index(
          digits.startIndex,
          offsetBy: Int.random(in: 0...count, using: &generator))
        digits.insert(".", at: point)
      }
      let sign = ["", "-", "+"][Int.random(in: 0..<3, using: &generator)]
      let exponent =
        Bool.random(using: &generator)
        ? "e\(Int.random(in: -30...30, using: &generator))" : ""
      assertAgrees(sign + digits + exponent, "seed \(seed)")
    }
  }

  // MARK: - The fast path

  /// How `DecimalParser.prefix` reads `text`: the value when its fast path
  /// converts it, and how many bytes the number takes.
  func prefix(_ text: String) -> (fast: Double?, length: Int?) {
    Array(text.utf8).withUnsafeBufferPointer { buffer in
      guard let start = buffer.baseAddress, !buffer.isEmpty else {
        return (nil, nil)
      }
      switch DecimalParser.prefix(from: start, to: start + buffer.count) {
      case .fast(let value, let end): return (value, end - start)
      case .slow(let end): return (nil, end - start)
      case .noDigits, .invalid: return (nil, nil)
      }
    }
  }

  /// Asserts the fast path converts `text`, all of it, to the standard
  /// library's correctly rounded value.
  func assertFast(
    _ text: String, _ context: @autoclosure () -> String = "",
    file: StaticString = #filePath, line: UInt = #line
  ) {
    let (fast, length) = prefix(text)
    guard let fast else {
      XCTFail(
        "\(text) is left to the slow path \(context())", file: file,
        line: line)
      return
    }
    XCTAssertEqual(length, text.utf8.count, text, file: file, line: line)
    XCTAssertEqual(
      fast.bitPattern, Double(text)?.bitPattern,
      "\(text): \(fast) vs \(Double(text).map { "\($0)" } ?? "nil") "
        + context(),
      file: file, line: line)
  }

  /// The fast path's edges: 19 significant digits, a mantissa of 2^53,
  /// exponents of ±22, leading and trailing zeros, zero.
  func testPrefix_FastPathLimits() {
    for text in [
      "9007199254740992", "9007199254740992e22", "9007199254740992e-22",
      "-9007199254740992e22", "1e22", "1e-22", "0.0000000000000000000001",
      "1e21", "0.9007199254740992", "900719925474099.2", "1.000000000000000",
      "0000000000000000000000000000001", "0", "-0", "0e22", "-0e-22",
      // 19 digits in all, leading zeros included, and 20, which are read
      // again without the zeros.
      "000000000000000001.5", "0000000000000000001.5", "0.000000000000000015",
      "0.0000000000000000015", "-123456789012345.6e-3",
    ] {
      assertFast(text)
    }
    for text in [
      "9007199254740993", "9007199254740993e-22", "1e23", "1e-23",
      "0.00000000000000000000001", "10000000000000000000000",
      "12345678901234567890", "1234567890123456789e1", "1e400", "4.9e-324",
      // Exact, but past the limits as counted: zeros are digits too.
      "1000000000000000000000", "1.000000000000000000", "0e-400",
      "0.000000000000000000000000000000e999",
    ] {
      XCTAssertNil(prefix(text).fast, text)
      XCTAssertEqual(prefix(text).length, text.utf8.count, text)
      assertAgrees(text)
    }
  }

  /// Where a number stops: at the first byte that cannot continue it.
  func testPrefix_StopsAtTheFirstByteNotPartOfTheNumber() {
    for (text, length) in [
      ("1.5x", 3), ("1e5e5", 3), ("-2.5}", 4), ("1..2", 2), ("7 8", 1),
      ("0x10", 1), ("1e+5.5", 4), ("12#", 2), ("3.{", 2),
    ] {
      XCTAssertEqual(prefix(text).length, length, text)
    }
    for text in ["-", "+", ".", "-.", "e5", "inf", "nan", "1e", "1e+", "2E-x"] {
      XCTAssertNil(prefix(text).length, text)
    }
  }

  /// Numbers as scene files write them take the fast path, and it gives
  /// the standard library's correctly rounded value: `%.7g` (what
  /// gen_spheres.py writes), the shortest round trip of a Float, and
  /// `%.15g` and the shortest round trip of a Double when their mantissa
  /// fits (below 2^53, exponent within ±22).
  func testPrefix_SceneShapesTakeTheFastPath() {
    forEachSeed(Self.seedCount(100_000), base: 0xDEC1_0003) { generator, seed in
      let value = generator.sign() * generator.logUniform(1e-8, 1e8)
      assertFast(String(format: "%.7g", value), "seed \(seed)")
      assertFast(String(format: "%.7e", value), "seed \(seed)")
      assertFast("\(Float(value))", "seed \(seed)")
      assertFast(String(format: "%.15g", value), "seed \(seed)")
      let shortest = "\(value)"
      if prefix(shortest).fast == nil {
        XCTAssertNil(prefix(String(format: "%.17g", value)).fast)
        assertAgrees(shortest, "seed \(seed)")
      } else {
        assertFast(shortest, "seed \(seed)")
      }
    }
  }

  /// Long mantissas and far exponents: whichever path converts them, the
  /// value is the standard library's.
  func testPrefix_LongMantissasAndFarExponents() {
    forEachSeed(Self.seedCount(50_000), base: 0xDEC1_0004) { generator, seed in
      let digits = (0..<Int.random(in: 1...40, using: &generator)).map { _ in
        String(Int.random(in: 0...9, using: &generator))
      }.joined()
      let exponent = Int.random(in: -340...320, using: &generator)
      assertAgrees("\(digits)e\(exponent)", "seed \(seed)")
      assertAgrees("0.\(digits)e\(exponent)", "seed \(seed)")
      let value = Double(bitPattern: generator.next() >> 1)
      if value.isFinite {
        assertAgrees(String(format: "%.17g", value), "seed \(seed)")
        assertAgrees(String(format: "%.7g", value), "seed \(seed)")
      }
    }
  }

  /// An odd integer q in [2^53/5, 2^54/5): 10q is then twice an odd
  /// 54-bit number, exactly halfway between two Doubles, and `qe1` reaches
  /// the fast path (q < 2^53).
  static func halfwayMantissa(using generator: inout SplitMix64) -> UInt64 {
    let low = (UInt64(1) << 53) / 5 + 1
    let high = (UInt64(1) << 54) / 5
    return UInt64.random(in: low..<high, using: &generator) | 1
  }

  /// Ties reach the fast path only through its multiplication (a quotient
  /// m / 10^k of m ≤ 2^53 is never halfway: that would need 5^k to
  /// divide a 54-bit odd number no larger than m); the product of exact
  /// operands is rounded once, ties to even: to the neighbour whose last
  /// significand bit is 0, which is also the standard library's value.
  func testPrefix_HalfwayProductsRoundToEven() {
    forEachSeed(20_000, base: 0xDEC1_0005) { generator, seed in
      let q = Self.halfwayMantissa(using: &generator)
      // 10q ≡ 2 (mod 4) in [2^54, 2^55), where Doubles are 4 apart.
      let below = Double(q * 10 - 2)
      let above = Double(q * 10 + 2)
      let even = below.significandBitPattern & 1 == 0 ? below : above
      for (text, sign) in [
        ("\(q)e1", 1.0), ("-\(q)e1", -1.0), ("+\(q)E+1", 1.0),
      ] {
        assertFast(text, "seed \(seed)")
        XCTAssertEqual(prefix(text).fast, sign * even, "\(text) seed \(seed)")
      }
    }
  }
}
