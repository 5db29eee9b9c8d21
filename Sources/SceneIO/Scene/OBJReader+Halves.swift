import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// A large OBJ file read on two threads: the first half as ever, the second
/// from a line break near the middle, speculatively, and joined where the
/// first ends.
///
/// The second half does not know what the first defines. A positive index
/// names the same element wherever it is read, so the second half keeps it
/// and records how many elements must precede it (`OBJParser.needed`); the
/// join checks that the first half defined that many. What reads otherwise
/// depending on the first half (a negative index, `a/b` before any `vt`
/// line) and every error stop the second half at the start of that
/// statement, with what it read before kept: the first thread reads on
/// from there itself, as the sequential parse would. So the mesh, and every
/// error with its line and column, are the sequential parse's.
extension OBJReader {
  /// Files from this size are read on two threads, where the machine has
  /// two processors: the scene parser's (`SceneParser.concurrentBytes`),
  /// not measured for OBJ files (docs/PERFORMANCE.md, "Large meshes").
  static let splitThreshold = 1 << 20

  /// The mesh of `bytes` read in two halves, or nil when the file has no
  /// line to split at near its middle (or one processor): the caller
  /// reads it on one thread then.
  static func parseInHalves(
    _ bytes: UnsafeBufferPointer<UInt8>, file: String, precision: Precision
  ) throws(SceneError) -> OBJMesh? {
    guard sysconf(Int32(_SC_NPROCESSORS_ONLN)) > 1,
      let split = splitPoint(bytes)
    else { return nil }
    var first = OBJParser(
      bytes: UnsafeBufferPointer(rebasing: bytes[..<split]), file: file,
      precision: precision)
    var second = OBJParser(bytes: bytes, file: file, precision: precision)
    second.index = split
    second.lineStart = split
    second.speculative = true
    var failure: SceneError?
    withUnsafeMutablePointer(to: &first) { first in
      withUnsafeMutablePointer(to: &second) { second in
        withUnsafeMutablePointer(to: &failure) { failure in
          let shared = Shared((first, second, failure))
          Parallel.inParts(2, 2) { part, _ in
            let (first, second, failure) = shared.value
            // Each parser read in a copy on its own thread's stack: the two
            // side by side here, written at every byte, shared cache lines
            // and made the two threads slower than one.
            if part == 0 {
              var parser = first.move()
              do throws(SceneError) {
                _ = try parser.parse()
              } catch {
                failure.pointee = error
              }
              first.initialize(to: parser)
            } else {
              var parser = second.move()
              parser.parseUntilStopped()
              second.initialize(to: parser)
            }
          }
        }
      }
    }
    // An error in the first half is the first error of the file.
    if let failure { throw failure }
    // The first half ended at `split`, on the line the second began with.
    // Each half's mesh is moved, not copied: the parsers let go of theirs.
    var reader = OBJParser(bytes: bytes, file: file, precision: precision)
    reader.index = split
    reader.lineStart = split
    reader.line = first.line
    reader.mesh = first.mesh
    first.mesh = OBJMesh()
    let limit = Int(Int32.max)
    let counts = (
      reader.mesh.vertices.count, reader.mesh.normals.count,
      reader.mesh.textureCoordinates.count
    )
    let added = (
      second.mesh.vertices.count, second.mesh.normals.count,
      second.mesh.textureCoordinates.count
    )
    if second.needed.vertices <= counts.0 && second.needed.normals <= counts.1
      && second.needed.textureCoordinates <= counts.2
      && counts.0 + added.0 <= limit && counts.1 + added.1 <= limit
      && counts.2 + added.2 <= limit
    {
      reader.mesh.append(contentsOf: second.mesh)
      second.mesh = OBJMesh()
      reader.index = second.index
      reader.lineStart = second.lineStart
      reader.line = first.line + second.line - 1
    }
    // Read on from where the second half stopped (its end, usually), or
    // from the split when its indices do not fit the first half's counts.
    return try reader.parse()
  }

  /// The start of a line near the middle of `bytes` after a line without
  /// a `\`, which therefore does not continue onto it; nil when there is
  /// none in the middle half of the file.
  static func splitPoint(_ bytes: UnsafeBufferPointer<UInt8>) -> Int? {
    var index = bytes.count / 2
    // Back to the start of the line holding the middle.
    while index > 0 && bytes[index - 1] != UInt8(ascii: "\n") {
      index -= 1
    }
    var clean = true
    while index < bytes.count * 3 / 4 {
      let byte = bytes[index]
      index += 1
      if byte == UInt8(ascii: "\\") {
        clean = false
      } else if byte == UInt8(ascii: "\n") {
        if clean { return index }
        clean = true
      }
    }
    return nil
  }
}

extension OBJParser {
  /// Reads statements to the end, or until one cannot be read here (an
  /// error, or what depends on the first half): the mesh is then as it
  /// was before that statement, and the parser at its start.
  mutating func parseUntilStopped() {
    while index < bytes.count {
      let start = (
        index: index, line: line, lineStart: lineStart, mesh: mesh.counts
      )
      do throws(SceneError) {
        if let keyword = nextToken() {
          try statement(keyword)
        }
      } catch {
        index = start.index
        line = start.line
        lineStart = start.lineStart
        mesh.truncate(to: start.mesh)
        return
      }
      if index < bytes.count {
        index += 1
        newLine()
      }
    }
  }
}

extension OBJMesh {
  /// The counts of elements and of index entries, for `truncate`.
  var counts: (elements: (Int, Int, Int), indices: (Int, Int, Int)) {
    (
      (vertices.count, normals.count, textureCoordinates.count),
      (vertexIndices.count, normalIndices.count, textureIndices.count)
    )
  }

  /// The mesh as it was when it had `counts`.
  mutating func truncate(
    to counts: (elements: (Int, Int, Int), indices: (Int, Int, Int))
  ) {
    vertices.removeLast(vertices.count - counts.elements.0)
    normals.removeLast(normals.count - counts.elements.1)
    textureCoordinates.removeLast(
      textureCoordinates.count - counts.elements.2)
    truncateIndices(to: counts.indices)
  }
}
