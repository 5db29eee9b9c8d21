import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// Plain vertex and face lines read in one pass (`plainVertex`,
/// `plainFace`) give the mesh, the `needed` counts of a part read
/// speculatively, and every message, of the token-by-token reading.
final class OBJPlainLinesTests: XCTestCase {
  /// Lines near the plain forms and just past them.
  static let lines = [
    "v 0 1.5 -2", "v 0.25\t-1e3 7", "v 1 2 3 ", "v  1 2 3\r", "v 1 2",
    "v 1 2 3 4", "v 1 2 3 0.5 0.5 0.5", "v 1 2 3 # note", "v 1e-400 0 0",
    "v 1e-40 2 3", "v 1e39 2 3", "v 1.00000000000000000001 2 3", "v 0 0 nan",
    "v +1 -0 .5", "v 1. 2 3e2", "v 1 2 3#", "v 1 2 x", "v 1 2 3 \\", "vn 0 0 1",
    "vt 0.5 0.5", "f 1 2 3", "f 1 2 3 4", "f 3 2 1 ", "f\t1\t2\t3\r",
    "f 1 2 3 4 5 6 7 8", "f 1 2 3 4 5 6 7 8 9", "f 1 2", "f 0 1 2",
    "f 1 2 99", "f -1 -2 -3", "f +1 2 3", "f 1/1 2/2 3/3", "f 1//1 2//1 3//1",
    "f 1 2 3/1", "f 1 2 3 # c", "f 1 2 3#", "f 01 002 3", "f 1 2 3x",
    "f 99999999999 1 2", "f 1 2 3 \\", "# comment", "", "g part", "o thing",
  ]

  /// Random texts of these lines, each parsed with and without the plain
  /// reading: whole, and as a later part read speculatively.
  func testPlainLines_AsTokenByToken() {
    var random = SplitMix64(seed: 11)
    for trial in 0..<3000 {
      var text = ""
      for _ in 0..<(1 + Int(random.next() % 12)) {
        let line = Self.lines[Int(random.next() % UInt64(Self.lines.count))]
        text += line + (random.next() % 8 == 0 ? "\r\n" : "\n")
      }
      if random.next() % 4 == 0 { text.removeLast() }
      for precision in [NumberRange.double, .float] {
        for speculative in [false, true] {
          let (plain, tokens) = (
            parsed(text, precision, speculative, plain: true),
            parsed(text, precision, speculative, plain: false)
          )
          guard plain == tokens else {
            return XCTFail(
              "trial \(trial), \(precision), speculative \(speculative): "
                + "\(text.debugDescription)\n\(plain)\n\(tokens)")
          }
        }
      }
    }
  }

  private func parsed(
    _ text: String, _ precision: NumberRange, _ speculative: Bool, plain: Bool
  ) -> String {
    let bytes = Array(text.utf8)
    return bytes.withUnsafeBufferPointer { bytes in
      var parser = OBJParser(bytes: bytes, file: "t.obj", precision: precision)
      parser.readsPlainLines = plain
      if speculative {
        parser.speculative = true
        parser.parseUntilStopped()
        return "\(parser.mesh.hashValue) \(parser.mesh.vertices) "
          + "\(parser.mesh.vertexIndices) \(parser.needed) "
          + "\(parser.index) \(parser.line) \(parser.lineStart)"
      }
      do {
        let mesh = try parser.parse()
        return "\(mesh.vertices) \(mesh.vertexIndices) \(mesh.normalIndices) "
          + "\(mesh.textureIndices)"
      } catch {
        return "\(error)"
      }
    }
  }
}
