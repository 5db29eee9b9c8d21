import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// `plainSphere`, the one-pass reading of spheres, against the token by
/// token reading it stands in for: the same values to the bit, the same
/// position afterwards, and through the parser the same scenes and errors.
final class SceneTokenizerTests: XCTestCase {
  /// The sphere's fields read token by token, when its body is the plain
  /// form, and the position after it.
  func tokenByToken(
    _ tokenizer: inout SceneTokenizer
  ) -> (values: [Double], position: SceneTokenizer.Position)? {
    guard tokenizer.next().kind == .open,
      tokenizer.matches(tokenizer.next(), "center")
    else { return nil }
    var values: [Double] = []
    for _ in 0..<3 {
      guard let value = tokenizer.number(tokenizer.next()) else { return nil }
      values.append(value)
    }
    guard tokenizer.matches(tokenizer.next(), "radius"),
      let radius = tokenizer.number(tokenizer.next()),
      tokenizer.next().kind == .close
    else { return nil }
    return (values + [radius], tokenizer.position)
  }

  /// Reads `body` (what follows `Sphere`) both ways, after a first line
  /// that offsets the position; returns whether `plainSphere` read it.
  @discardableResult
  func assertAgrees(
    _ body: String, _ context: @autoclosure () -> String = "",
    file: StaticString = #filePath, line: UInt = #line
  ) -> Bool {
    let bytes = Array("Group {\n  Sphere\(body) }\n".utf8)
    var plain = SceneTokenizer(bytes: bytes)
    _ = plain.next()
    _ = plain.next()
    _ = plain.next()
    var tokens = plain
    let before = plain.position
    let read = plain.plainSphere()
    let expected = tokenByToken(&tokens)
    guard let read else {
      XCTAssertEqual(
        plain.position, before,
        "position moved: \(body.debugDescription) \(context())",
        file: file, line: line)
      return false
    }
    guard let expected else {
      XCTFail(
        "read \(body.debugDescription), which is no plain sphere \(context())",
        file: file, line: line)
      return true
    }
    let got = [read.center.x, read.center.y, read.center.z, read.radius]
    XCTAssertEqual(
      got.map(\.bitPattern), expected.values.map(\.bitPattern),
      "\(body.debugDescription): \(got) vs \(expected.values) \(context())",
      file: file, line: line)
    XCTAssertEqual(
      plain.position, expected.position,
      "\(body.debugDescription) \(context())",
      file: file, line: line)
    return true
  }

  func testPlainSphere_ReadsTheCommonForms() {
    for body in [
      " { center -4.4012876 -9.251321 -9.559668  radius 0.01254766 }",
      "{center 0 0 0 radius 1}",
      " {\n  center 1 2 3\n  radius 4\n}",
      "\t{\tcenter\t+1.5\t-0\t.5\tradius\t5.}",
      " {\r\n center 1e-5 2E+3 0.000000000000000000001 radius 1e22 }",
      " { center 9007199254740992 -1234567890123456 1.5e-7 radius 2 }",
      " { center 0 0 0 radius -1 }",  // read: the parser refuses it
      "\u{0B}{\u{0C}center 1 2 3 radius 4 }",
    ] {
      XCTAssertTrue(assertAgrees(body), body.debugDescription)
    }
  }

  /// Everything the token by token reading must see for itself: its
  /// errors, comments, the slow path's numbers and non-finite words.
  func testPlainSphere_LeavesOtherFormsToTheTokens() {
    for body in [
      " { radius 1 center 0 0 0 }", " { center 0 0 0 }", " { radius 1 }",
      " { center 0 0 radius 1 }", " { center 0 0 0 0 radius 1 }",
      " { center 0 0 0 radius 1 radius 2 }",
      " { # comment\n center 0 0 0 radius 1 }",
      " { center 0 0 0# x\n radius 1 }", " { center 1e23 0 0 radius 1 }",
      " { center 1e-23 0 0 radius 1 }",
      " { center 9007199254740993 0 0 radius 1 }",
      " { center 12345678901234567890 0 0 radius 1 }",
      " { center 1e400 0 0 radius 1 }",
      " { center 4.9e-324 0 0 radius 1 }", " { center inf 0 0 radius 1 }",
      " { center nan 0 0 radius 1 }", " { center 1.5x 0 0 radius 1 }",
      " { center 1e 0 0 radius 1 }", " { center . 0 0 radius 1 }",
      " { center 0x10 0 0 radius 1 }", " { center 1\u{0} 0 0 radius 1 }",
      " { centerx 0 0 0 radius 1 }", " { Center 0 0 0 radius 1 }",
      " { center{ 0 0 0 radius 1 }", " { center 0 0 0 radius 1{ }",
      " center 0 0 0 radius 1 }", "",
      " { center \(String(repeating: "0", count: 4096))1 0 0 radius 1 }",
    ] {
      XCTAssertFalse(assertAgrees(body), body.debugDescription)
    }
    // Leading zeros up to the parser's word limit are still the fast path.
    XCTAssertTrue(
      assertAgrees(
        " { center \(String(repeating: "0", count: 4095))1 0 0 radius 1 }"))
  }

  func testPlainSphere_AtEndOfFile() {
    for text in ["", "{", "{ center", "{ center 1 2 3 radius 4"] {
      var tokenizer = SceneTokenizer(bytes: Array(text.utf8))
      let before = tokenizer.position
      XCTAssertNil(tokenizer.plainSphere(), text)
      XCTAssertEqual(tokenizer.position, before, text)
    }
    var tokenizer = SceneTokenizer(
      bytes: Array("{ center 1 2 3 radius 4 }".utf8))
    XCTAssertEqual(tokenizer.plainSphere()?.radius, 4)
    XCTAssertEqual(tokenizer.next().kind, .end)
  }

  /// Random sphere bodies: numbers in the shapes scene files and printf
  /// write (`%.7g`, `%.17g`, the shortest round trip, exponents, leading
  /// zeros, long mantissas) and the slow path's and refused words, blanks
  /// of every kind, line breaks and comments between the tokens, and the
  /// fields sometimes swapped. Every plain body whose numbers the fast
  /// path converts must be read, and read as the tokens are.
  func testPlainSphere_RandomBodiesMatchTokenByToken() {
    var read = 0
    forEachSeed(20_000, base: 0x5_B0D1) { generator, seed in
      let (body, plain) = Self.randomBody(using: &generator)
      let wasRead = assertAgrees(body, "seed \(seed)")
      XCTAssertEqual(wasRead, plain, "\(body.debugDescription) seed \(seed)")
      if wasRead { read += 1 }
    }
    print("plain spheres read: \(read) of 20000")
    XCTAssertGreaterThan(read, 2_000)
  }

  /// Scenes of random spheres parse to the same bits, or fail with the
  /// same error at the same position, with and without `plainSphere`,
  /// on one thread and on two.
  func testParse_RandomSpheresMatchTokenByToken() {
    var outcomes = (parsed: 0, failed: 0)
    forEachSeed(300, base: 0x5_B0D2) { generator, seed in
      let count = Int.random(in: 1...40, using: &generator)
      var text = SceneParserTests.camera + "Group {\n  numObjects \(count)\n"
      // One sphere with mistakes in about half the scenes, so that many
      // parse and many fail.
      let mistaken = Int.random(in: 0..<(2 * count), using: &generator)
      for index in 0..<count {
        text +=
          "  Sphere"
          + Self.randomBody(using: &generator, mistakes: index == mistaken).body
          + "\n"
      }
      text += "}\n"
      let bytes = Array(text.utf8)
      var results: [Result<Scene, SceneError>] = []
      for (plain, concurrent) in [(true, false), (false, false), (true, true)] {
        var parser = SceneParser(bytes: bytes, file: "t.txt")
        parser.readsPlainSpheres = plain
        do throws(SceneError) {
          if concurrent {
            var spliced = 0
            results.append(
              .success(
                try SceneParser.parse(
                  bytes: bytes, file: "t.txt", concurrentFrom: (1, 1),
                  spliced: &spliced)))
          } else {
            results.append(.success(try parser.parseScene()))
          }
        } catch {
          results.append(.failure(error))
        }
      }
      for other in results.dropFirst() {
        switch (results[0], other) {
        case (.success(let one), .success(let two)):
          XCTAssertEqual(
            Self.sphereBits(one.root), Self.sphereBits(two.root), "seed \(seed)"
          )
        case (.failure(let one), .failure(let two)):
          XCTAssertEqual(one, two, "seed \(seed)")
        default:
          XCTFail("seed \(seed): \(results[0]) against \(other)")
        }
      }
      switch results[0] {
      case .success: outcomes.parsed += 1
      case .failure: outcomes.failed += 1
      }
    }
    print("random sphere scenes: \(outcomes)")
    XCTAssertGreaterThan(outcomes.parsed, 30)
    XCTAssertGreaterThan(outcomes.failed, 30)
  }

  /// The errors a sphere's numbers give are the token by token reading's.
  func testParse_SphereNumberErrorsUnchanged() {
    for (field, column, message) in [
      (
        "center 1e400 0 0 radius 1", 19,
        "'1e400' is beyond the finite range of double "
          + "(±1.7976931348623157e+308)"
      ),
      ("center 0 0 0 radius -1", 32, "'radius' must be positive, found -1"),
      ("center 0 0 0 radius 0", 32, "'radius' must be positive, found 0"),
      (
        "center 0 0 0 radius 1e-400", 32,
        "'1e-400' rounds to zero in double (its smallest normal number is "
          + "2.2250738585072014e-308)"
      ),
      ("center 0 0 0 radius nan", 32, "expected a finite number, found 'nan'"),
      ("center 0 0 0 radius 1.5x", 32, "expected a number, found '1.5x'"),
    ] {
      let text =
        SceneParserTests.camera
        + "Group {\n  numObjects 1\n  Sphere { \(field) }\n}\n"
      do throws(SceneError) {
        _ = try SceneParser.parse(text, file: "t.txt")
        XCTFail("parsed \(field)")
      } catch {
        XCTAssertEqual(
          error.description, "t.txt:4:\(column): error: \(message)")
      }
    }
  }

  // MARK: - Helpers

  /// Each sphere's center, radius and material, as bits: `==` on Double
  /// would take −0 for 0.
  static func sphereBits(_ group: Group<Double>) -> [UInt64] {
    group.objects.flatMap { object -> [UInt64] in
      guard case .sphere(let sphere) = object else { return [UInt64.max] }
      return [
        sphere.center.x.bitPattern, sphere.center.y.bitPattern,
        sphere.center.z.bitPattern, sphere.radius.bitPattern,
        UInt64(sphere.materialIndex),
      ]
    }
  }

  /// A sphere's body, and whether it is the plain form with numbers the
  /// fast path converts, judged by `DecimalParser.prefix` on each word.
  /// Without `mistakes`, the body is a valid sphere, though not always a
  /// plain one.
  static func randomBody(
    using generator: inout SplitMix64, mistakes: Bool = true
  ) -> (body: String, plain: Bool) {
    var plain = true
    func gap(_ optional: Bool) -> String {
      let gaps = [" ", "  ", "\t", "\n", "\r\n", " \u{0B}", "\n\n    "]
      if optional && Int.random(in: 0..<4, using: &generator) == 0 { return "" }
      if Int.random(in: 0..<25, using: &generator) == 0 {
        plain = false
        return " # a comment { 1 }\n"
      }
      return gaps[Int.random(in: 0..<gaps.count, using: &generator)]
    }
    func number(positive: Bool = false) -> String {
      var text = randomNumber(using: &generator, mistakes: mistakes)
      if positive && !mistakes {
        if text.hasPrefix("-") { text.removeFirst() }
        if Double(text) == 0 { text = "1" }
      }
      let bytes = Array(text.utf8)
      let fast = bytes.withUnsafeBufferPointer { buffer -> Bool in
        guard let start = buffer.baseAddress, !buffer.isEmpty,
          case .fast(_, let end) = DecimalParser.prefix(
            from: start, to: start + buffer.count)
        else { return false }
        return end == start + buffer.count
      }
      if !fast { plain = false }
      return text
    }
    let center =
      "center" + gap(false) + number() + gap(false) + number() + gap(false)
      + number()
    let radius = "radius" + gap(false) + number(positive: true)
    var fields = [center, radius]
    if Int.random(in: 0..<15, using: &generator) == 0 {
      fields.swapAt(0, 1)
      plain = false
    }
    if mistakes && Int.random(in: 0..<30, using: &generator) == 0 {
      fields.removeLast()
      plain = false
    }
    let body =
      gap(true) + "{" + gap(true) + fields.joined(separator: gap(false))
      + gap(true) + "}"
    return (body, plain)
  }

  /// Mostly what scene writers print, sometimes what only the slow path
  /// or the parser's errors handle.
  static func randomNumber(
    using generator: inout SplitMix64, mistakes: Bool = true
  ) -> String {
    let value = generator.sign() * generator.logUniform(1e-8, 1e8)
    switch Int.random(in: 0..<(mistakes ? 20 : 17), using: &generator) {
    case 0...5: return String(format: "%.7g", value)
    case 6...7: return String(format: "%.17g", value)
    case 8...9: return "\(value)"
    case 10: return "\(Float(value))"
    case 11: return String(format: "%.3e", value)
    case 12: return "\(Int(value))"
    case 13: return "+" + String(format: "%07.3f", abs(value))
    case 14:
      let digits = (0..<Int.random(in: 15...25, using: &generator)).map { _ in
        String(Int.random(in: 0...9, using: &generator))
      }.joined()
      return "0." + digits
    case 15:
      return "\(Int.random(in: 1...999, using: &generator))e"
        + "\(Int.random(in: -30...30, using: &generator))"
    case 16:
      // Every binade but the top one, where a product can overflow.
      return String(format: "%.17g", Double(bitPattern: generator.next() >> 2))
    case 17:
      return ["0", "-0", "0.0", "-0e5", "1e400", "1e-400", "inf", "nan"][
        Int.random(in: 0..<8, using: &generator)]
    case 18:
      // Exact ties of the fast path's multiplication; see
      // DecimalParserTests.testPrefix_HalfwayProductsRoundToEven.
      return "\(DecimalParserTests.halfwayMantissa(using: &generator))e1"
    default:
      return ["1.5x", ".", "-", "1e", "1..2", "0x1p3", "", "1,5"][
        Int.random(in: 0..<8, using: &generator)]
    }
  }
}
