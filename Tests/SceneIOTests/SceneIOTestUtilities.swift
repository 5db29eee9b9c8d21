import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

// Helpers of the readers' tests: well-formed errors, word ranges for the
// mutation tests, and an OBJ mesh's faces as model triangles.

// MARK: - Scene errors

/// Asserts that `error` is one well-formed line whose position lies within
/// `bytes` (a column may point just past a line's end).
func assertWellFormed(
  _ error: SceneError, in bytes: [UInt8], seed: UInt64,
  file: StaticString = #filePath, line: UInt = #line
) {
  let description = error.description
  XCTAssertFalse(
    description.contains("\n"), "seed \(seed): more than one line", file: file,
    line: line)
  XCTAssertTrue(
    description.hasPrefix(
      "\(error.file):\(error.line):\(error.column): error: "),
    "seed \(seed): malformed description \(description.debugDescription)",
    file: file, line: line)
  let lines = bytes.split(
    separator: UInt8(ascii: "\n"), omittingEmptySubsequences: false)
  XCTAssertTrue(
    (1...lines.count).contains(error.line),
    "seed \(seed): line \(error.line) of \(lines.count)", file: file, line: line
  )
  if (1...lines.count).contains(error.line) {
    XCTAssertTrue(
      (1...(lines[error.line - 1].count + 1)).contains(error.column),
      "seed \(seed): column \(error.column) on line \(error.line)", file: file,
      line: line)
  }
}

/// The byte ranges of the blank-separated words of `bytes`, for the
/// mutation tests' edits.
func wordRanges(_ bytes: [UInt8]) -> [Range<Int>] {
  var ranges: [Range<Int>] = []
  var start: Int?
  for (index, byte) in bytes.enumerated() {
    let blank = byte == 0x20 || byte == 0x0A || byte == 0x09
    if blank, let begun = start {
      ranges.append(begun..<index)
      start = nil
    } else if !blank && start == nil {
      start = index
    }
  }
  if let begun = start { ranges.append(begun..<bytes.count) }
  return ranges
}

extension OBJMesh {
  /// Every face as a model triangle in precision S (`triangle(at:)`).
  func makeTriangles<S: RayScalar>(
    materialIndex: Int, as _: S.Type = S.self
  ) -> [Triangle<S>] {
    (0..<triangleCount).map {
      triangle(at: $0, materialIndex: materialIndex, as: S.self)
    }
  }

  /// The model triangle of `triangles[index]` in precision S, with vertex
  /// normals and texture coordinates where the face gave them, for callers
  /// that store each one straight into their own array. A degenerate
  /// triangle (a repeated vertex, a zero-area face) is made as any other:
  /// it is never hit, and dropping it is the compiled scene's choice.
  ///
  /// - Precondition: `0 <= index < triangleCount`.
  func triangle<S: RayScalar>(
    at index: Int, materialIndex: Int, as _: S.Type = S.self
  ) -> Triangle<S> {
    let face = face(index)
    let v = face.vertexIndices
    let normals = face.normalIndices.map { n in
      Triangle<S>.VertexNormals(
        Vector3<S>(self.normals[Int(n.x)]),
        Vector3<S>(self.normals[Int(n.y)]),
        Vector3<S>(self.normals[Int(n.z)]))
    }
    let coordinates = face.textureIndices.map { t in
      Triangle<S>.TextureCoordinates(
        TextureCoordinate<S>(textureCoordinates[Int(t.x)]),
        TextureCoordinate<S>(textureCoordinates[Int(t.y)]),
        TextureCoordinate<S>(textureCoordinates[Int(t.z)]))
    }
    return Triangle<S>(
      Vector3<S>(vertices[Int(v.x)]), Vector3<S>(vertices[Int(v.y)]),
      Vector3<S>(vertices[Int(v.z)]), vertexNormals: normals,
      textureCoordinates: coordinates, materialIndex: materialIndex)
  }
}
