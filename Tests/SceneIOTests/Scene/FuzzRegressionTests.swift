import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// What fuzzing the parser (Fuzz/FuzzSceneParser.swift, run by Fuzz/run.sh)
/// found, and the limits it relies on: every input parses or fails with one
/// line at its position, and no input allocates or works beyond what its
/// size warrants. SceneParserTests holds the format's own errors; the
/// nesting and count limits are extended here, not repeated.
final class FuzzRegressionTests: XCTestCase {
  static let camera = SceneParserTests.camera
  static let sphere = SceneParserTests.sphere

  static var packageRoot: String {
    return ProjectFiles.projectFolder
  }

  /// The fuzzer's committed seed corpus of scenes.
  static var corpus: String { packageRoot + "/Fuzz/corpus/scene" }

  /// Asserts that `bytes` fail to parse with exactly `message` at
  /// `line`:`column`, in the one-line form; returns the parser, whose
  /// reservations the limit tests inspect.
  @discardableResult
  func assertError(
    _ bytes: [UInt8], line: Int, column: Int, _ message: String,
    file: StaticString = #filePath, line testLine: UInt = #line
  ) -> SceneParser {
    var parser = SceneParser(bytes: bytes, file: "test.txt")
    do throws(SceneError) {
      _ = try parser.parseScene()
      XCTFail("parsed without error", file: file, line: testLine)
    } catch {
      XCTAssertEqual(error.message, message, file: file, line: testLine)
      XCTAssertEqual(
        "\(error.line):\(error.column)", "\(line):\(column)", file: file,
        line: testLine)
      XCTAssertEqual(
        error.description, "test.txt:\(line):\(column): error: \(message)",
        file: file, line: testLine)
    }
    return parser
  }

  @discardableResult
  func assertError(
    _ text: String, line: Int, column: Int, _ message: String,
    file: StaticString = #filePath, line testLine: UInt = #line
  ) -> SceneParser {
    assertError(
      Array(text.utf8), line: line, column: column, message, file: file,
      line: testLine)
  }

  func parse(_ text: String) throws(SceneError) -> Scene {
    try SceneParser.parse(text, file: "test.txt")
  }

  /// A group of `count` copies of `object` (the format has no shorter way
  /// to write many objects).
  func group(_ count: Int, _ object: String) -> String {
    "Group { numObjects \(count)\n"
      + String(repeating: object + "\n", count: count) + "}\n"
  }

  // MARK: - The seed corpus

  /// Every seed of the fuzzer parses, or fails with one line of the form
  /// `FILE:LINE:COLUMN: error: MESSAGE` at a position inside the file.
  func testCorpus_EveryFileParsesOrFailsOnOneLine() throws {
    let names = try FileManager.default.contentsOfDirectory(atPath: Self.corpus)
      .sorted()
    XCTAssertGreaterThanOrEqual(
      names.count, 30, "the corpus is at \(Self.corpus)")
    var outcomes = (parsed: 0, failed: 0)
    for name in names {
      let path = Self.corpus + "/" + name
      do throws(SceneError) {
        _ = try SceneParser.parse(contentsOf: path)
        outcomes.parsed += 1
      } catch {
        outcomes.failed += 1
        let description = error.description
        XCTAssertTrue(
          description.hasPrefix(
            "\(path):\(error.line):\(error.column): error: "),
          "\(name): \(description)")
        XCTAssertFalse(description.contains("\n"), "\(name): \(description)")
        XCTAssertGreaterThanOrEqual(error.line, 1, "\(name): \(description)")
        XCTAssertGreaterThanOrEqual(error.column, 1, "\(name): \(description)")
      }
    }
    // The corpus seeds both outcomes; a parser that refused everything, or
    // nothing, would show here.
    XCTAssertGreaterThanOrEqual(outcomes.parsed, 15, "\(outcomes)")
    XCTAssertGreaterThanOrEqual(outcomes.failed, 25, "\(outcomes)")
  }

  // MARK: - Word length

  /// A word of exactly `maximumWordLength` bytes is read as usual.
  func testWordLength_AtTheLimitParses() throws {
    let radius =
      "1." + String(repeating: "0", count: SceneParser.maximumWordLength - 2)
    let scene = try parse(
      Self.camera
        + "Group { numObjects 1 Sphere { center 0 0 0 radius \(radius) } }")
    XCTAssertEqual(
      scene.root, Group([.sphere(Sphere(center: .zero, radius: 1))]))
  }

  /// One byte more is an error at the word, quoting its start.
  func testWordLength_BeyondTheLimitIsAnError() {
    let radius =
      "1." + String(repeating: "0", count: SceneParser.maximumWordLength - 1)
    assertError(
      Self.camera
        + "Group { numObjects 1 Sphere { center 0 0 0 radius \(radius) } }",
      line: 2, column: 51,
      "a word of 4097 bytes ('1.0000000000000000000000…') is longer than the "
        + "limit of 4096 bytes")
    assertError(
      Self.camera + String(repeating: "a", count: 5000), line: 2, column: 1,
      "a word of 5000 bytes ('aaaaaaaaaaaaaaaaaaaaaaaa…') is longer than the "
        + "limit of 4096 bytes")
  }

  /// Before the limit a 50 MB word took 6 s in a release build (compared
  /// with each keyword for a suggestion) and was quoted whole: a 52 MB
  /// "line" of error.
  /// (Eight megabytes unless RAYTRACE_LONG_TESTS.)
  func testWordLength_FiftyMegabyteWord() {
    let count = (runsLongTests ? 50 : 8) << 20
    let bytes = [UInt8](repeating: UInt8(ascii: "a"), count: count)
    assertError(
      bytes, line: 1, column: 1,
      "a word of \(count) bytes ('aaaaaaaaaaaaaaaaaaaaaaaa…') is longer than "
        + "the limit of 4096 bytes")
  }

  /// Comments and blanks have no limit: only words are quoted or compared.
  func testWordLength_LongCommentsAndLinesAreFine() throws {
    let comment = "# " + String(repeating: "x", count: 1 << 20) + "\n"
    let scene = try parse(comment + Self.camera + group(1, Self.sphere))
    XCTAssertEqual(scene.root.objects.count, 1)

    // A megabyte-long line still reports its column exactly.
    assertError(
      Self.camera + String(repeating: " ", count: 1_000_000) + "Teapot",
      line: 2, column: 1_000_001,
      "expected a block name, found 'Teapot' (expected one of "
        + "'PerspectiveCamera', 'Lights', 'Background', 'Materials', 'Group')")
  }

  // MARK: - Garbage

  /// 50 MB of random bytes fail at the first word, on one line.
  func testGarbage_FiftyMegabytes() {
    var generator = SplitMix64(seed: 0xF022_0050)
    // Eight bytes per draw: a debug build fills 50 MB in about a second.
    var words = [UInt64](repeating: 0, count: (50 << 20) / 8)
    for index in words.indices {
      words[index] = generator.next()
    }
    let bytes = words.withUnsafeBytes { Array($0) }
    do throws(SceneError) {
      _ = try SceneParser.parse(bytes: bytes, file: "test.txt")
      XCTFail("random bytes parsed")
    } catch {
      XCTAssertTrue(
        error.description.hasPrefix("test.txt:1:"), error.description)
      XCTAssertFalse(error.description.contains("\n"), error.description)
      XCTAssertLessThan(error.description.utf8.count, 200, error.description)
    }
  }

  // MARK: - Messages

  /// Control characters and line separators in a quoted word are escaped,
  /// so that the message stays one line and cannot drive a terminal;
  /// suggestions still come from the word as written. Invalid UTF-8 shows
  /// as U+FFFD.
  func testMessages_ControlCharactersAreEscaped() {
    let blocks =
      "(expected one of 'PerspectiveCamera', 'Lights', 'Background', "
      + "'Materials', 'Group')"
    assertError(
      Self.camera + "Gr\u{1B}[2Joup { }", line: 2, column: 1,
      "expected a block name, found 'Gr\\u{1B}[2Joup' \(blocks)")
    assertError(
      Self.camera + "Gro\u{2028}up { }", line: 2, column: 1,
      "expected a block name, found 'Gro\\u{2028}up' \(blocks)")
    assertError(
      Self.camera + "Group\u{85} { }", line: 2, column: 1,
      "expected a block name, found 'Group\\u{85}'; did you mean 'Group'?")
    assertError(
      Self.camera + "Group { numObjects 1 Sph\u{0}ere { } }", line: 2,
      column: 22,
      "expected an object, found 'Sph\\u{0}ere'; did you mean 'Sphere'?")
    assertError(
      Array(Self.camera.utf8) + [0x47, 0x72, 0xFF, 0x75, 0x70], line: 2,
      column: 1, "expected a block name, found 'Gr\u{FFFD}up' \(blocks)")
  }

  // MARK: - Counts and reservations

  /// A declared count is believed only as far as the file could hold that
  /// many objects (19 bytes each at least): `numObjects 999999999999` is
  /// read, reported against what follows, and reserves nothing beyond it.
  func testCounts_HugeCountReservesOnlyWhatTheFileCouldHold() {
    let text = Self.camera + "Group { numObjects 999999999999 \(Self.sphere) }"
    let parser = assertError(
      text, line: 2, column: 66,
      "Group has 1 object but numObjects (line 2) says 999999999999")
    XCTAssertLessThanOrEqual(
      parser.reservedObjects, text.utf8.count / SceneParser.minimumObjectLength)

    assertError(
      Self.camera + "Group { numObjects 1e15 \(Self.sphere) }", line: 2,
      column: 20, "'numObjects' must be at most 999999999999999, found 1e15")
  }

  /// Before the budget, each of 200 nested groups reserved its declared
  /// million objects: 5 KB of text held 1.6 GB of address space, and a
  /// process limited to 1.5 GB trapped ("failed to allocate 8000024 bytes").
  func testCounts_NestedLyingCountsShareOneBudget() {
    let depth = SceneParser.maximumGroupDepth
    let text =
      Self.camera
      + String(repeating: "Group { numObjects 999999\n", count: depth)
    let parser = assertError(
      text, line: depth + 2, column: 1,
      "unexpected end of file: Group is missing its '}'")
    XCTAssertLessThanOrEqual(
      parser.reservedObjects, text.utf8.count / SceneParser.minimumObjectLength)
  }

  /// An honest count is reserved in full, as the million-sphere files need.
  func testCounts_HonestCountIsReservedInFull() throws {
    let text = Self.camera + group(1000, Self.sphere)
    var parser = SceneParser(bytes: Array(text.utf8), file: "test.txt")
    let scene = try parser.parseScene()
    XCTAssertEqual(scene.root.objects.count, 1000)
    XCTAssertEqual(parser.reservedObjects, 1000)
  }

  /// The shortest object is 19 bytes: the budget's divisor must not exceed
  /// it, or an honest file of the shortest objects would be under-reserved.
  func testCounts_MinimumObjectLength() throws {
    let shortest = "Group{numObjects 0}"
    XCTAssertEqual(shortest.utf8.count, SceneParser.minimumObjectLength)
    let text =
      Self.camera + "Group{numObjects 3 \(shortest)\(shortest)\(shortest)}"
    XCTAssertEqual(try parse(text).root.objects.count, 3)
  }

  // MARK: - Nesting

  /// A million nested groups on one line (19 MB) stop at the limit, at the
  /// exact column, without descending further.
  func testNesting_MillionLevelsStopAtTheLimit() {
    let level = "Group{numObjects 1 "
    let depth = SceneParser.maximumGroupDepth
    assertError(
      Self.camera + String(repeating: level, count: 1_000_000), line: 2,
      column: 1 + depth * level.utf8.count,
      "Groups and Transforms are nested more than \(depth) deep")
  }

  // MARK: - Planes

  /// Found by the fuzzer's check that a parsed scene holds only finite
  /// numbers: `Plane` divides the offset by the normal's length, which
  /// overflowed to an infinite offset for a tiny normal and a large offset.
  /// The plane now fails at its offset.
  func testPlane_OffsetOverTinyNormalOverflows() {
    assertError(
      Self.camera
        + "Group { numObjects 1 Plane { normal 0 0 1e-150 offset 1e300 } }",
      line: 2, column: 55,
      "the plane is too far from the origin: offset 1e300 divided by the "
        + "normal's length is not a finite number")
  }

  /// The same tiny normal with an offset to match is the plane z = 1.
  func testPlane_TinyNormalWithMatchingOffset() throws {
    let scene = try parse(
      Self.camera
        + "Group { numObjects 1 Plane { normal 0 0 1e-150 offset 1e-150 } }")
    XCTAssertEqual(
      scene.root, Group([.plane(Plane(normal: Vector3(0, 0, 1), offset: 1))]))
  }
}
