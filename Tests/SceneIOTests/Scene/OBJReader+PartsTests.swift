import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// An OBJ file read in parts on several threads (`OBJReader.parseInParts`)
/// gives the mesh, or the error at its line and column, that one thread
/// gives, whatever the later parts hold and however many there are.
final class OBJReaderPartsTests: XCTestCase {
  /// A grid of n × n quads: its vertices, then its faces, each written
  /// `form` ("v", "v/vt", "v//vn", "v/vt/vn"), with an element of each kind
  /// per vertex.
  func grid(_ n: Int, form: String = "v", interleaved: Bool = false)
    -> [String]
  {
    var vertices: [String] = []
    for row in 0...n {
      for column in 0...n {
        vertices.append("v \(column) \(row) \(Double(row * column) / 7)")
        vertices.append("vn 0 \(Double(row) / 9) 1")
        vertices.append("vt \(Double(column) / 5) 0.5")
      }
    }
    func reference(_ index: Int) -> String {
      switch form {
      case "v/vt": "\(index)/\(index)"
      case "v//vn": "\(index)//\(index)"
      case "v/vt/vn": "\(index)/\(index)/\(index)"
      default: "\(index)"
      }
    }
    var faces: [String] = []
    for row in 0..<n {
      for column in 0..<n {
        let a = row * (n + 1) + column + 1
        let corners: [Int] = [a, a + 1, a + n + 2, a + n + 1]
        let references: [String] = corners.map(reference)
        faces.append("f " + references.joined(separator: " "))
      }
    }
    guard interleaved else { return vertices + faces }
    // Each row's faces after the vertices they use.
    var lines: [String] = []
    let perRow = 3 * (n + 1)
    for row in 0...n {
      let start: Int = row * perRow
      lines += vertices[start..<(start + perRow)]
      if row > 0 { lines += faces[((row - 1) * n)..<(row * n)] }
    }
    return lines
  }

  /// `bytes` as "mesh.obj" read in two halves, or its error.
  static func readInHalves(_ bytes: [UInt8]) -> Result<OBJMesh, SceneError> {
    read(bytes, parts: 2)
  }

  /// `bytes` as "mesh.obj" read in `parts` parts however small (on one
  /// thread for 1), or its error.
  static func read(_ bytes: [UInt8], parts: Int = 1) -> Result<
    OBJMesh, SceneError
  > {
    do throws(SceneError) {
      return .success(
        try OBJReader.parse(bytes: bytes, file: "mesh.obj", parts: parts))
    } catch {
      return .failure(error)
    }
  }

  /// The part counts every reading is checked with.
  static let partCounts = [2, 3, 7, 16]

  func assertSame(
    _ lines: [String], _ label: String, file: StaticString = #filePath,
    line: UInt = #line
  ) {
    let bytes = Array((lines.joined(separator: "\n") + "\n").utf8)
    let one = Self.read(bytes)
    for parts in Self.partCounts {
      XCTAssertEqual(
        Self.read(bytes, parts: parts), one, "\(label), \(parts) parts",
        file: file, line: line)
    }
  }

  func testParts_AsOneThread_EveryForm() {
    for form in ["v", "v/vt", "v//vn", "v/vt/vn"] {
      for interleaved in [false, true] {
        assertSame(grid(12, form: form, interleaved: interleaved), form)
      }
    }
  }

  /// Lines whose reading depends on the first half, or that are wrong,
  /// placed in the second half (the last lines of the file).
  func testParts_AsOneThread_SecondHalfLines() {
    let cases = [
      "f -1 -2 -3", "f 1 2 -1", "f 1/1 2/2 3/3", "f 1//1 2//2 3//3",
      "f 1 2 999999", "f 0 1 2", "f 1 2", "v 1 2", "x 1 2 3",
      "f 1/1/1 2/2/2 3/3/999999", "vn 1 0 0\nf 1/1 2/2 3/3",
      "vt 0 0\nf 1/1 2/2 3/3", "f 1 2 \\\n 3", "v 1 2 \\\n 3\nf -1 1 2",
      "f 1 2 3 # \\", "f 1 2 3\r", "f 1e3 2 3", "v 1 2 nan",
    ]
    for text in cases {
      for (name, first) in [
        ("vertices only", "v 0 0 0\nv 1 0 0\nv 0 1 0"),
        ("all three", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0"),
        ("normals", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 1 0 0"),
      ] {
        let padding = Array(
          repeating: "# padding for the first half", count: 40)
        let tail = Array(repeating: "f 1 2 3", count: 30)
        assertSame(
          [first] + padding + tail + [text] + tail, "\(name): \(text)")
      }
    }
  }

  /// Files too small or without a line to split at near their middle,
  /// and empty ones, read on one thread as ever.
  func testParts_NoSplit() {
    assertSame([], "empty")
    let continued = Array(repeating: " \\", count: 50)
    assertSame(["v 0 0 0 \\"] + continued, "one line")
    XCTAssertEqual(
      OBJReader.splitPoints(
        UnsafeBufferPointer(start: nil, count: 0), parts: 16), [])
  }

  /// A mesh in 1, 2, 3, 7 and 16 parts: the same mesh, split at as many
  /// places as asked, and lines whose reading depends on earlier parts or
  /// that are wrong, placed in every part.
  func testParts_AnyCount_SameMeshOrError() {
    let lines = grid(24, form: "v/vt/vn", interleaved: true)
    let bytes = Array((lines.joined(separator: "\n") + "\n").utf8)
    let one = Self.read(bytes)
    guard case .success(let mesh) = one else {
      return XCTFail("the grid does not parse")
    }
    XCTAssertEqual(mesh.triangleCount, 2 * 24 * 24)
    for parts in [2, 3, 7, 16] {
      let splits = bytes.withUnsafeBufferPointer {
        OBJReader.splitPoints($0, parts: parts)
      }
      XCTAssertEqual(splits.count, parts - 1, "\(parts) parts")
      XCTAssertEqual(Self.read(bytes, parts: parts), one, "\(parts) parts")
    }
    // Each wrong or dependent line in turn at 1/8, 3/8, 5/8 and 7/8 of the
    // file: in several parts' middles, for each count.
    for text in ["f -1 -2 -3", "f 1/1 2/2 3/3", "f 1 2 999999", "x 1 2"] {
      for eighth in [1, 3, 5, 7] {
        var mutated = lines
        mutated.insert(text, at: lines.count * eighth / 8)
        assertSame(mutated, "\(text) at \(eighth)/8")
      }
    }
  }
}
