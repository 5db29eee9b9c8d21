import Geometry
import SceneDescription
import PlatformSupport

/// Reads the polygon meshes of Wavefront OBJ files, as `TriangleMesh
/// { obj_file … }` names them:
///
///     v x y z [w]          a vertex (w, a curve weight, is checked, unused)
///     v x y z r g b        a vertex with a colour (checked, unused)
///     vn x y z             a normal, for smooth shading
///     vt u [v [w]]         a texture coordinate (v defaults to 0; w is
///                          checked, unused)
///     f v1 v2 v3 …         a polygon, each vertex v, v/vt, v//vn or v/vt/vn
///     o g s mg usemtl mtllib usemap maplib lod bevel c_interp d_interp
///     ctech stech shadow_obj trace_obj   (ignored: they name, group or
///                                         decorate, and change no geometry)
///     # …                  a comment, to the end of the line, also after
///                          a statement
///
/// Indices start at 1; a negative index counts back from the last element
/// defined so far (−1 is the latest). Every index must refer to an element
/// defined above the face, as the OBJ specification has it; a forward
/// reference is reported as out of range. A polygon with n > 3 vertices is
/// split into the fan (v1, vi, vi+1), i = 2…n−1, which is exact for the
/// convex, planar polygons exporters write. All vertices of one face must
/// use the same form (all with normals or none, all with texture
/// coordinates or none), so a face is never half smooth-shaded; different
/// faces may use different forms. A line ending in `\` continues on the
/// next line. Empty files give an empty mesh.
///
/// `a/b` is read as the Swift course's loader reads it: b is a texture
/// coordinate when the file has defined `vt` lines before the face, and a
/// normal when it has defined only `vn` lines (the course's files write
/// normals that way). Where a file has both, `OBJMesh.
/// readingTextureIndicesAsNormals()` gives the loader's reading for a
/// material without a texture.
///
/// Every problem is a `SceneError` at its byte's line and column, with a
/// one-line message; no input traps, including bytes that are not UTF-8,
/// NUL bytes, and numbers too large for Double or Int. Line elements (`l`,
/// `p`) and free-form geometry (`curv`, `surf`, …) are reported as not
/// supported rather than skipped, so a mesh is never silently incomplete.
///
/// - Complexity: one pass over the bytes; numbers are converted by
///   `DecimalParser`'s fast path. See OBJReaderTests for the measured rate.
package enum OBJReader {
  /// Reads and parses the file at `path`; `path` names the file in
  /// messages. A file that cannot be read is an error with line 0. Every
  /// number must be held by `precision` (see `NumberRange.rangeProblem`).
  /// A large file is read and parsed by up to `threads` threads, one part
  /// each (`parseInParts`): the mesh, or the error, is the same for any
  /// count.
  package static func read(
    contentsOf path: String, precision: NumberRange = .double, threads: Int = 1
  ) throws(SceneError) -> OBJMesh {
    let bytes: SceneBytes
    do {
      bytes = try SceneBytes.contentsOf(path, threads: threads)
    } catch {
      throw SceneError(file: path, line: 0, column: 0, message: error.reason)
    }
    let parts = Parallel.parts(
      bytes.buffer.count, threads: threads, from: splitThreshold,
      minimum: splitThreshold / 2)
    return try parse(
      bytes.buffer, file: path, precision: precision, parts: parts)
  }

  /// Parses `text`; `file` names it in messages.
  package static func parse(
    _ text: String, file: String, precision: NumberRange = .double
  ) throws(SceneError) -> OBJMesh {
    try parse(bytes: Array(text.utf8), file: file, precision: precision)
  }

  /// Parses raw bytes, which need not be valid UTF-8, in `parts` parts
  /// however small (`parseInParts`; tests split small files).
  static func parse(
    bytes: [UInt8], file: String, precision: NumberRange = .double,
    parts: Int = 1
  ) throws(SceneError) -> OBJMesh {
    try bytes.withUnsafeBufferPointer { (buffer) throws(SceneError) in
      try parse(buffer, file: file, precision: precision, parts: parts)
    }
  }

  /// Parses `bytes` in `parts` parts, each on its own thread, or on one
  /// thread where there is one part or no line to split at.
  static func parse(
    _ bytes: UnsafeBufferPointer<UInt8>, file: String, precision: NumberRange,
    parts: Int
  ) throws(SceneError) -> OBJMesh {
    if parts > 1,
      let mesh = try parseInParts(
        bytes, file: file, precision: precision, parts: parts)
    {
      return mesh
    }
    var parser = OBJParser(bytes: bytes, file: file, precision: precision)
    return try parser.parse()
  }
}

// MARK: - Parser

/// One pass over an OBJ file's bytes. Errors are thrown as `SceneError`.
struct OBJParser {
  let bytes: UnsafeBufferPointer<UInt8>
  let file: String
  /// The render's precision, which must hold every number.
  let precision: NumberRange
  var index = 0
  var line = 1
  var lineStart = 0
  /// Where the last token read ended, for "found end of line" messages.
  var lastEnd = (line: 1, column: 1)
  var mesh = OBJMesh()
  /// Set for a later part of a file read in parts
  /// (`OBJReader.parseInParts`), which does not know what the parts
  /// before it define: an index past the elements read so far is
  /// recorded in `needed` rather than refused, and anything whose reading
  /// depends on the parts before (a negative index, `a/b` before any `vt`
  /// line) is an error that stops the part there.
  var speculative = false
  /// In a speculative half, per kind of element, how many must come before
  /// it for every index read to be valid.
  var needed = (vertices: 0, normals: 0, textureCoordinates: 0)
  /// Whether plain vertex and face lines are read in one pass
  /// (`plainVertex`, `plainFace`); tests turn it off to compare the mesh
  /// and the messages with the token-by-token reading's.
  var readsPlainLines = true

  /// The statements that name, group or decorate geometry without changing
  /// it, and are skipped with their arguments.
  static let ignored: Set<String> = [
    "o", "g", "s", "mg", "usemtl", "mtllib", "usemap", "maplib", "lod",
    "bevel", "c_interp", "d_interp", "ctech", "stech", "shadow_obj",
    "trace_obj",
  ]

  /// Valid OBJ statements for free-form curves and surfaces.
  static let freeForm: Set<String> = [
    "vp", "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm",
    "trim", "hole", "scrv", "sp", "end", "con",
  ]

  /// The keywords suggested for a misspelling.
  static let keywords = [
    "v", "vn", "vt", "f", "o", "g", "s", "usemtl", "mtllib",
  ]

  /// Longer unknown keywords are not compared with the keywords: no
  /// misspelling is that long, and the comparison would cost the square of
  /// the length.
  static let longestSuggestible = 32

  /// Quoted tokens are cut here, so a message stays one readable line.
  static let longestQuoted = 48

  struct Token {
    var start: Int
    var end: Int
    var line: Int
    var column: Int
  }

  /// How a face vertex is written: which of v, vt, vn it gives.
  enum Form: Equatable {
    case vertex, vertexTexture, vertexNormal, vertexTextureNormal

    var spelling: String {
      switch self {
      case .vertex: "v"
      case .vertexTexture: "v/vt"
      case .vertexNormal: "v//vn"
      case .vertexTextureNormal: "v/vt/vn"
      }
    }
  }

  /// What an index refers to, for messages.
  enum Element {
    case vertex, textureCoordinate, normal

    var singular: String {
      switch self {
      case .vertex: "vertex"
      case .textureCoordinate: "texture coordinate"
      case .normal: "normal"
      }
    }

    var plural: String {
      switch self {
      case .vertex: "vertices"
      case .textureCoordinate: "texture coordinates"
      case .normal: "normals"
      }
    }
  }

  init(
    bytes: UnsafeBufferPointer<UInt8>, file: String,
    precision: NumberRange = .double
  ) {
    self.bytes = bytes
    self.file = file
    self.precision = precision
    // A UTF-8 byte-order mark (editors on Windows write one) is not part
    // of the first line: columns count from after it.
    if bytes.starts(with: utf8ByteOrderMark) {
      index = utf8ByteOrderMark.count
      lineStart = index
    }
  }

  mutating func parse() throws(SceneError) -> OBJMesh {
    while index < bytes.count {
      if let keyword = nextToken() {
        try statement(keyword)
      }
      // Each statement stops at its line's end: a newline or the file's end.
      if index < bytes.count {
        index += 1
        newLine()
      }
    }
    return mesh
  }
}
