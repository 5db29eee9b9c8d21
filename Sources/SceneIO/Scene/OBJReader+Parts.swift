import Geometry
import SceneDescription
import PlatformSupport

/// A large OBJ file read in parts on several threads, one per thread: the
/// first part as ever, each other from a line break near its share of the
/// file, speculatively, and joined in order where the one before ends.
///
/// A later part does not know what the parts before it define. A positive
/// index names the same element wherever it is read, so the part keeps it
/// and records how many elements must precede it (`OBJParser.needed`); the
/// join checks that the parts before defined that many. What reads
/// otherwise depending on earlier parts (a negative index, `a/b` before
/// any `vt` line) and every error stop the part at the start of that
/// statement, with what it read before kept: the join reads on from there
/// to the part's end itself, as the sequential parse would (the whole part
/// when its indices do not fit). So the mesh, and every error with its
/// line and column, are the sequential parse's, whatever the parts.
extension OBJReader {
  /// Files from this size are read in parts of at least half of it, one
  /// per thread: the scene parser's (`SceneParser.concurrentBytes`), not
  /// measured for OBJ files (docs/PERFORMANCE.md, "Large meshes").
  static let splitThreshold = 1 << 20

  /// The mesh of `bytes` read in up to `parts` parts, or nil when the
  /// file has no line to split at near any part's start: the caller reads
  /// it on one thread then.
  static func parseInParts(
    _ bytes: UnsafeBufferPointer<UInt8>, file: String, precision: NumberRange,
    parts: Int
  ) throws(SceneError) -> OBJMesh? {
    let splits = splitPoints(bytes, parts: parts)
    guard !splits.isEmpty else { return nil }
    let bounds = [0] + splits + [bytes.count]
    let count = bounds.count - 1
    // Each part's parser sees the file up to its part's end, which is a
    // line's end: the sequential parse's view of its last line.
    func parser(_ part: Int, from start: Int) -> OBJParser {
      var parser = OBJParser(
        bytes: UnsafeBufferPointer(rebasing: bytes[..<bounds[part + 1]]),
        file: file, precision: precision)
      if part > 0 {
        parser.index = start
        parser.lineStart = start
      }
      return parser
    }
    var parsers = (0..<count).map { part in
      var speculative = parser(part, from: bounds[part])
      speculative.speculative = part > 0
      return speculative
    }
    var failure: SceneError?
    parsers.withUnsafeMutableBufferPointer { parsers in
      withUnsafeMutablePointer(to: &failure) { failure in
        let shared = Shared((parsers, failure))
        Parallel.inParts(count, count) { part, _ in
          let (parsers, failure) = shared.value
          // Each parser read in a copy on its own thread's stack: two side
          // by side, written at every byte, shared cache lines and made two
          // threads slower than one.
          var parser = (parsers.baseAddress! + part).move()
          if part == 0 {
            do throws(SceneError) {
              _ = try parser.parse()
            } catch {
              failure.pointee = error
            }
          } else {
            parser.parseUntilStopped()
          }
          (parsers.baseAddress! + part).initialize(to: parser)
        }
      }
    }
    // An error in the first part is the first error of the file.
    if let failure { throw failure }
    // Each part's mesh is moved, not copied: the parsers let go of theirs,
    // the first part's arrays grown once to hold them all.
    var mesh = parsers[0].mesh
    parsers[0].mesh = OBJMesh()
    mesh.reserveCapacity(adding: parsers[1...].map(\.mesh.counts))
    var line = parsers[0].line
    for part in 1..<count {
      var (index, lineStart) = (bounds[part], bounds[part])
      if parsers[part].fits(after: mesh) {
        mesh.append(contentsOf: parsers[part].mesh)
        parsers[part].mesh = OBJMesh()
        line += parsers[part].line - 1
        (index, lineStart) = (parsers[part].index, parsers[part].lineStart)
      }
      // Read on from where the part stopped (its end, usually), or from
      // its start when its indices do not fit the parts' before it.
      guard index < bounds[part + 1] else { continue }
      var reader = parser(part, from: index)
      reader.lineStart = lineStart
      reader.line = line
      reader.mesh = mesh
      mesh = OBJMesh()
      _ = try reader.parse()
      mesh = reader.mesh
      reader.mesh = OBJMesh()
      line = reader.line
    }
    return mesh
  }

  /// The starts of the parts `parseInParts` reads `bytes` in, increasing:
  /// for each part after the first, the start of a line near its share
  /// (`splitPoint`), none for a part that has no such line before half of
  /// its share.
  static func splitPoints(_ bytes: UnsafeBufferPointer<UInt8>, parts: Int)
    -> [Int]
  {
    var points: [Int] = []
    for part in 1..<Swift.max(1, parts) {
      let (near, limit) = (
        bytes.count * part / parts, bytes.count * (2 * part + 1) / (2 * parts)
      )
      if let point = splitPoint(bytes, near: near, before: limit),
        point > points.last ?? 0
      {
        points.append(point)
      }
    }
    return points
  }

  /// The start of a line at or after the line holding `near` and before
  /// `limit`, after a line without a `\`, which therefore does not
  /// continue onto it; nil when there is none.
  static func splitPoint(
    _ bytes: UnsafeBufferPointer<UInt8>, near: Int, before limit: Int
  ) -> Int? {
    var index = Swift.min(near, bytes.count)
    // Back to the start of the line holding `near`.
    while index > 0 && bytes[index - 1] != UInt8(ascii: "\n") {
      index -= 1
    }
    var clean = true
    while index < Swift.min(limit, bytes.count) {
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
  /// Whether this speculative part's mesh can follow `mesh`: every index it
  /// read is defined by then, and the counts stay within Int32.
  func fits(after before: OBJMesh) -> Bool {
    let limit = Int(Int32.max)
    return needed.vertices <= before.vertices.count
      && needed.normals <= before.normals.count
      && needed.textureCoordinates <= before.textureCoordinates.count
      && before.vertices.count + mesh.vertices.count <= limit
      && before.normals.count + mesh.normals.count <= limit
      && before.textureCoordinates.count + mesh.textureCoordinates.count
        <= limit
  }

  /// Reads statements to the end, or until one cannot be read here (an
  /// error, or what depends on the parts before): the mesh is then as it
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

  /// Room for the elements and index entries of meshes of `counts` after
  /// this one's: one copy of its arrays where appending grew them by
  /// doubling, a copy each time, beside every later part's arrays.
  mutating func reserveCapacity(
    adding counts: [(elements: (Int, Int, Int), indices: (Int, Int, Int))]
  ) {
    var total = self.counts
    for added in counts {
      total.elements.0 += added.elements.0
      total.elements.1 += added.elements.1
      total.elements.2 += added.elements.2
      total.indices.0 += added.indices.0
    }
    vertices.reserveCapacity(total.elements.0)
    normals.reserveCapacity(total.elements.1)
    textureCoordinates.reserveCapacity(total.elements.2)
    reserveIndices(total.indices.0)
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
