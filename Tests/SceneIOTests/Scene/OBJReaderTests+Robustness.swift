import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

extension OBJReaderTests {
  // MARK: - Robustness

  /// Mutated meshes (words deleted, duplicated or replaced; bytes deleted
  /// or inserted) either parse or throw one well-formed one-line error
  /// pointing inside the text. A trap would end the run. Read in two to
  /// four parts (`parseInParts`), each gives the same mesh or the same
  /// error.
  func testParse_MutatedMeshesNeverTrap() throws {
    let original = Array(
      (Self.elements
        + "f 1 2 3\nf 1/1 2/2 4/3\nf 1//1 3//2 4//3 2//1\nf 2/1/3 3/2/2 4/3/1\n"
        + "# done\ng group\n").utf8)
    let replacements = [
      "f", "v", "vn", "vt", "0", "-1", "-5", "99999999999999999999", "1e999",
      "nan", "1//", "/", "1/1/1/1", "\\", "#", "\u{0}", "é", "\r", "\n",
      "usemtl",
      "l", "2//2", "3/3",
    ]
    var outcomes = (parsed: 0, failed: 0)
    forEachSeed(2000, base: 0x0B1_0001) { generator, seed in
      var bytes = original
      for _ in 0..<Int.random(in: 1...4, using: &generator) {
        mutate(&bytes, replacements: replacements, using: &generator)
      }
      do throws(SceneError) {
        _ = try OBJReader.parse(bytes: bytes, file: "mesh.obj")
        outcomes.parsed += 1
      } catch {
        outcomes.failed += 1
        assertWellFormed(error, in: bytes, seed: seed)
      }
      XCTAssertEqual(
        OBJReaderPartsTests.read(bytes, parts: 2 + Int(seed % 3)),
        OBJReaderPartsTests.read(bytes), "seed \(seed)")
    }
    print("mutated meshes: \(outcomes)")
    // Both outcomes must occur, or the mutations are too weak or too strong.
    XCTAssertGreaterThan(outcomes.parsed, 20)
    XCTAssertGreaterThan(outcomes.failed, 500)
  }

  /// One random edit: a word deleted, duplicated or replaced, or a byte
  /// deleted or inserted.
  func mutate(
    _ bytes: inout [UInt8], replacements: [String],
    using generator: inout SplitMix64
  ) {
    let words = wordRanges(bytes)
    guard !words.isEmpty else {
      bytes.append(contentsOf: "f".utf8)
      return
    }
    let word = words[Int.random(in: 0..<words.count, using: &generator)]
    switch Int.random(in: 0..<5, using: &generator) {
    case 0:
      bytes.removeSubrange(word)
    case 1:
      bytes.insert(contentsOf: Array(bytes[word]) + [0x20], at: word.lowerBound)
    case 2:
      let replacement = replacements[
        Int.random(in: 0..<replacements.count, using: &generator)]
      bytes.replaceSubrange(word, with: Array(replacement.utf8))
    case 3:
      bytes.remove(at: Int.random(in: 0..<bytes.count, using: &generator))
    default:
      bytes.insert(
        UInt8.random(in: 0...255, using: &generator),
        at: Int.random(in: 0...bytes.count, using: &generator))
    }
  }
}
