import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

extension SceneParserTests {
  // MARK: - Robustness

  /// Mutated scenes (tokens deleted, duplicated, swapped or replaced;
  /// bytes deleted or inserted) either parse or throw one well-formed
  /// one-line error pointing inside the text. A trap would end the run.
  func testParse_MutatedScenesNeverTrap() throws {
    let original = Array(Self.full.utf8)
    let replacements = [
      "{", "}", "Group", "Sphere", "Plane", "MaterialIndex", "numObjects", "-1",
      "0",
      "1e999", "nan", "-inf", "1e-400", "0.5", "99999999999999999999",
      "PerspectiveCamera",
      "Transform", "#", "é", "\u{0}", "Materials", "numMaterials", "180",
      "radius",
    ]
    var outcomes = (parsed: 0, failed: 0)
    forEachSeed(2000, base: 0xF022_0001) { generator, seed in
      var bytes = original
      for _ in 0..<Int.random(in: 1...4, using: &generator) {
        mutate(&bytes, replacements: replacements, using: &generator)
      }
      let text = String(decoding: bytes, as: UTF8.self)
      do throws(SceneError) {
        _ = try parse(text)
        outcomes.parsed += 1
      } catch {
        outcomes.failed += 1
        assertWellFormed(error, in: Array(text.utf8), seed: seed)
      }
    }
    print("mutated scenes: \(outcomes)")
    // Both outcomes must occur, or the mutations are too weak or too strong.
    XCTAssertGreaterThan(outcomes.parsed, 20)
    XCTAssertGreaterThan(outcomes.failed, 1000)
  }

  /// A large group read on two threads gives the sequential parse's scene
  /// or error, to the line and column, whatever the file: mutated scenes
  /// of spheres, material indices, comments, a nested group, a transform
  /// and a plane, split near their middle.
  func testParse_GroupReadOnTwoThreads_MatchesOneThread() throws {
    var lines = [
      Self.camera.trimmingCharacters(in: .newlines),
      "Materials { numMaterials 3 Material { diffuseColor 1 0 0 }",
      "  Material { diffuseColor 0 1 0 } Material { diffuseColor 0 0 1 } }",
      "Group {", "  numObjects 57", "  MaterialIndex 1",
    ]
    for index in 0..<60 {
      switch index {
      case 5:
        lines.append(
          "  Group { numObjects 1 Sphere { center 0 0 1 radius 2 } }")
      case 8:
        lines.append(
          "  Transform { Translate 1 0 0 Sphere { radius 1 center 0 0 0 } }")
      case 10: lines.append("  Plane { normal 0 1 0 offset -2 }")
      case 12: lines.append("  MaterialIndex 2  # a comment {")
      case 45: lines.append("  MaterialIndex 0")
      case 50: lines.append("  # Sphere { center")
      default:
        lines.append(
          "  Sphere { center \(index) -\(index).5 0.25  radius 0.\(index + 1) }"
        )
      }
    }
    lines.append("}")
    let original = Array(lines.joined(separator: "\n").utf8)
    let replacements = [
      "{", "}", "Group", "Sphere", "MaterialIndex", "7", "-1", "nan", "#",
      "radius", "center", "numObjects", "\n",
    ]
    var outcomes = (parsed: 0, failed: 0, spliced: 0)
    let seeds = Self.seedCount(1500)
    forEachSeed(seeds, base: 0x2_7EAD) { generator, seed in
      var bytes = original
      if seed != 0x2_7EAD {
        for _ in 0..<Int.random(in: 1...3, using: &generator) {
          mutate(&bytes, replacements: replacements, using: &generator)
        }
      }
      let one: Result<Scene, SceneError>
      let two: Result<Scene, SceneError>
      var spliced = 0
      do throws(SceneError) {
        one = .success(try SceneParser.parse(bytes: bytes, file: "t.txt"))
      } catch {
        one = .failure(error)
      }
      do throws(SceneError) {
        two = .success(
          try SceneParser.parse(
            bytes: bytes, file: "t.txt", concurrentFrom: (1, 1),
            spliced: &spliced))
      } catch {
        two = .failure(error)
      }
      if spliced > 0 { outcomes.spliced += 1 }
      if seed == 0x2_7EAD {
        XCTAssertGreaterThan(spliced, 10, "the unmutated scene is split")
      }
      switch (one, two) {
      case (.success(let one), .success(let two)):
        outcomes.parsed += 1
        XCTAssertEqual(one.root, two.root, "seed \(seed)")
      case (.failure(let one), .failure(let two)):
        outcomes.failed += 1
        XCTAssertEqual(one, two, "seed \(seed)")
      default:
        XCTFail("seed \(seed): \(one) against \(two)")
      }
    }
    print("group read on two threads: \(outcomes)")
    // Of 1500 seeds (RAYTRACE_LONG_TESTS) more than 100, 300 and 300.
    XCTAssertGreaterThan(outcomes.parsed, seeds / 15)
    XCTAssertGreaterThan(outcomes.failed, seeds / 5)
    XCTAssertGreaterThan(outcomes.spliced, seeds / 5)
  }

  func mutate(
    _ bytes: inout [UInt8], replacements: [String],
    using generator: inout SplitMix64
  ) {
    let tokens = wordRanges(bytes)
    guard !tokens.isEmpty, !bytes.isEmpty else {
      bytes.append(contentsOf: "Group".utf8)
      return
    }
    let token = tokens[Int.random(in: 0..<tokens.count, using: &generator)]
    switch Int.random(in: 0..<6, using: &generator) {
    case 0:
      bytes.removeSubrange(token)
    case 1:
      bytes.insert(
        contentsOf: Array(bytes[token]) + [0x20], at: token.lowerBound)
    case 2:
      let replacement = replacements[
        Int.random(in: 0..<replacements.count, using: &generator)]
      bytes.replaceSubrange(token, with: Array(replacement.utf8))
    case 3:
      let other = tokens[Int.random(in: 0..<tokens.count, using: &generator)]
      if other.lowerBound > token.upperBound {
        let (first, second) = (Array(bytes[token]), Array(bytes[other]))
        bytes.replaceSubrange(other, with: first)
        bytes.replaceSubrange(token, with: second)
      }
    case 4:
      bytes.remove(at: Int.random(in: 0..<bytes.count, using: &generator))
    default:
      bytes.insert(
        UInt8.random(in: 0...255, using: &generator),
        at: Int.random(in: 0...bytes.count, using: &generator))
    }
  }
}
