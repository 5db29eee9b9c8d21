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
public enum OBJReader {
  /// Reads and parses the file at `path`; `path` names the file in
  /// messages. A file that cannot be read is an error with line 0.
  public static func read(contentsOf path: String) throws(SceneError) -> OBJMesh
  {
    let bytes: [UInt8]
    do {
      bytes = try readFile(path)
    } catch {
      throw SceneError(file: path, line: 0, column: 0, message: error.reason)
    }
    return try parse(bytes: bytes, file: path)
  }

  /// Parses `text`; `file` names it in messages.
  public static func parse(_ text: String, file: String) throws(SceneError)
    -> OBJMesh
  {
    try parse(bytes: Array(text.utf8), file: file)
  }

  /// Parses raw bytes, which need not be valid UTF-8.
  static func parse(bytes: [UInt8], file: String) throws(SceneError) -> OBJMesh
  {
    try bytes.withUnsafeBufferPointer { (buffer) throws(SceneError) in
      var parser = OBJParser(bytes: buffer, file: file)
      return try parser.parse()
    }
  }
}

// MARK: - Parser

/// One pass over an OBJ file's bytes. Errors are thrown as `SceneError`.
struct OBJParser {
  let bytes: UnsafeBufferPointer<UInt8>
  let file: String
  private var index = 0
  private var line = 1
  private var lineStart = 0
  /// Where the last token read ended, for "found end of line" messages.
  private var lastEnd = (line: 1, column: 1)
  private var mesh = OBJMesh()

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

  init(bytes: UnsafeBufferPointer<UInt8>, file: String) {
    self.bytes = bytes
    self.file = file
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

  // MARK: Statements

  private mutating func statement(_ keyword: Token) throws(SceneError) {
    let length = keyword.end - keyword.start
    let first = bytes[keyword.start]
    if length == 1 {
      switch first {
      case UInt8(ascii: "v"): return try vertex(keyword)
      case UInt8(ascii: "f"): return try face(keyword)
      default: break
      }
    } else if length == 2 && first == UInt8(ascii: "v") {
      switch bytes[keyword.start + 1] {
      case UInt8(ascii: "n"): return try normal(keyword)
      case UInt8(ascii: "t"): return try textureCoordinate(keyword)
      default: break
      }
    }
    if length <= Self.longestSuggestible {
      let word = String(
        decoding: slice(keyword.start, keyword.end), as: UTF8.self)
      if Self.ignored.contains(word) {
        skipRestOfLine()
        return
      }
    }
    throw unknown(keyword)
  }

  /// `v x y z`, `v x y z w` or `v x y z r g b`.
  private mutating func vertex(_ keyword: Token) throws(SceneError) {
    guard mesh.vertices.count < Int(Int32.max) else {
      throw error(
        at: keyword, "too many vertices: at most \(Int32.max) are supported")
    }
    let x = try coordinate("the x coordinate", of: "v")
    let y = try coordinate("the y coordinate", of: "v")
    let z = try coordinate("the z coordinate", of: "v")
    if let fourth = nextToken() {
      _ = try number(fourth, "w", of: "v")
      if let fifth = nextToken() {
        // Six numbers: the fourth was the red of a vertex colour.
        _ = try number(fifth, "g", of: "v x y z r g b")
        _ = try coordinate("b", of: "v x y z r g b")
        try endOfLine(after: "v x y z r g b")
      }
    }
    mesh.vertices.append(Vector3(x, y, z))
  }

  /// `vn x y z`.
  private mutating func normal(_ keyword: Token) throws(SceneError) {
    // Normal indices are stored as Int32, as vertex indices are.
    guard mesh.normals.count < Int(Int32.max) else {
      throw error(
        at: keyword, "too many normals: at most \(Int32.max) are supported")
    }
    let x = try coordinate("the x coordinate", of: "vn")
    let y = try coordinate("the y coordinate", of: "vn")
    let z = try coordinate("the z coordinate", of: "vn")
    try endOfLine(after: "vn x y z")
    mesh.normals.append(Vector3(x, y, z))
  }

  /// `vt u [v [w]]`: (u, v), v 0 when it is not given.
  private mutating func textureCoordinate(_ keyword: Token) throws(SceneError) {
    guard mesh.textureCoordinates.count < Int(Int32.max) else {
      throw error(
        at: keyword,
        "too many texture coordinates: at most \(Int32.max) are supported")
    }
    let u = try coordinate("the u coordinate", of: "vt")
    var v = 0.0
    if let second = nextToken() {
      v = try number(second, "the v coordinate", of: "vt")
      if let third = nextToken() {
        _ = try number(third, "the w coordinate", of: "vt")
        try endOfLine(after: "vt u v w")
      }
    }
    mesh.textureCoordinates.append(TextureCoordinate(u, v))
  }

  /// `f` and three or more vertex references, fanned into triangles as they
  /// are read.
  private mutating func face(_ keyword: Token) throws(SceneError) {
    var count = 0
    var first:
      (token: Token, vertex: Int32, normal: Int32, texture: Int32, form: Form)?
    var previous: (vertex: Int32, normal: Int32, texture: Int32) = (0, 0, 0)
    while let token = nextToken() {
      let reference = try faceVertex(token)
      if let first {
        guard reference.form == first.form else {
          throw error(
            at: token,
            "face vertex '\(quote(token))' has the form "
              + "\(reference.form.spelling), but the face's first vertex "
              + "'\(quote(first.token))' has the form \(first.form.spelling); "
              + "all vertices of a face must use the same form")
        }
        if count >= 2 {
          mesh.triangles.append(
            OBJTriangle(
              vertexIndices: SIMD3(
                first.vertex, previous.vertex, reference.vertex),
              normalIndices: first.normal < 0
                ? nil : SIMD3(first.normal, previous.normal, reference.normal),
              textureIndices: first.texture < 0
                ? nil
                : SIMD3(first.texture, previous.texture, reference.texture)))
        }
      } else {
        first = (
          token, reference.vertex, reference.normal, reference.texture,
          reference.form
        )
      }
      previous = (reference.vertex, reference.normal, reference.texture)
      count += 1
    }
    guard count >= 3 else {
      throw error(
        at: keyword, "a face needs at least 3 vertices, found \(count)")
    }
  }

  /// One face vertex, `v`, `v/vt`, `v//vn` or `v/vt/vn`: its 0-based vertex
  /// index, its 0-based normal and texture indices or −1, and its form.
  private mutating func faceVertex(
    _ token: Token
  ) throws(SceneError) -> (
    vertex: Int32, normal: Int32, texture: Int32, form: Form
  ) {
    // The parts between slashes, found without allocating: this runs three
    // times per triangle.
    var firstSlash = token.end
    var secondSlash = token.end
    var slashes = 0
    for position in token.start..<token.end
    where bytes[position] == UInt8(ascii: "/") {
      switch slashes {
      case 0: firstSlash = position
      case 1: secondSlash = position
      default: throw malformedFaceVertex(token)
      }
      slashes += 1
    }
    let vertexPart = (start: token.start, end: firstSlash)
    let texturePart = (start: firstSlash + 1, end: secondSlash)
    let normalPart = (start: secondSlash + 1, end: token.end)
    let form: Form
    switch slashes {
    case 0: form = .vertex
    case 1: form = .vertexTexture
    default:
      form =
        texturePart.start == texturePart.end
        ? .vertexNormal : .vertexTextureNormal
    }
    guard vertexPart.start < vertexPart.end,
      form != .vertexTexture || texturePart.start < texturePart.end,
      slashes < 2 || normalPart.start < normalPart.end
    else { throw malformedFaceVertex(token) }
    let vertex = try resolve(
      vertexPart, of: token, .vertex, count: mesh.vertices.count)
    var normal: Int32 = -1
    var texture: Int32 = -1
    if form == .vertexTexture && mesh.textureCoordinates.isEmpty
      && !mesh.normals.isEmpty
    {
      // The course's `a/b` with only normals defined: b is a normal.
      normal = try resolve(
        texturePart, of: token, .normal, count: mesh.normals.count)
    } else if form == .vertexTexture || form == .vertexTextureNormal {
      texture = try resolve(
        texturePart, of: token, .textureCoordinate,
        count: mesh.textureCoordinates.count)
    }
    if form == .vertexNormal || form == .vertexTextureNormal {
      normal = try resolve(
        normalPart, of: token, .normal, count: mesh.normals.count)
    }
    return (vertex, normal, texture, form)
  }

  /// The 0-based index that the 1-based or negative index in `part` names,
  /// among `count` elements defined so far.
  private func resolve(
    _ part: (start: Int, end: Int), of token: Token, _ element: Element,
    count: Int
  ) throws(SceneError) -> Int32 {
    let partToken = Token(
      start: part.start, end: part.end, line: token.line,
      column: token.column + (part.start - token.start))
    guard let written = integer(part.start, part.end) else {
      throw error(
        at: partToken,
        "expected an integer \(element.singular) index, found "
          + "'\(quote(partToken))'")
    }
    if written == 0 {
      throw error(
        at: partToken,
        "\(element.singular) index 0 is invalid: OBJ indices start at 1; "
          + defined(count, element))
    }
    let resolved = written > 0 ? written - 1 : count + written
    guard resolved >= 0 && resolved < count else {
      throw error(
        at: partToken,
        "\(element.singular) index \(quote(partToken)) is out of range: "
          + defined(count, element))
    }
    return Int32(truncatingIfNeeded: resolved)
  }

  /// How many elements an index may refer to, and the valid indices.
  private func defined(_ count: Int, _ element: Element) -> String {
    switch count {
    case 0: "no \(element.plural) are defined before this face"
    case 1: "1 \(element.singular) is defined before this face (valid: 1 or -1)"
    default:
      "\(count) \(element.plural) are defined before this face "
        + "(valid: 1 to \(count) or -\(count) to -1)"
    }
  }

  /// [+-]digits as an Int, saturated at ±2⁶² (beyond any element count);
  /// nil for anything else.
  private func integer(_ start: Int, _ end: Int) -> Int? {
    var position = start
    var negative = false
    if position < end
      && (bytes[position] == UInt8(ascii: "-")
        || bytes[position] == UInt8(ascii: "+"))
    {
      negative = bytes[position] == UInt8(ascii: "-")
      position += 1
    }
    guard position < end else { return nil }
    var value = 0
    let limit = 1 << 62
    while position < end {
      let digit = bytes[position] &- UInt8(ascii: "0")
      guard digit < 10 else { return nil }
      // Below limit / 10 the next step cannot pass 2⁶³; past it, saturate.
      value = value < limit / 10 ? value * 10 + Int(digit) : limit
      position += 1
    }
    return negative ? -value : value
  }

  // MARK: Numbers

  /// The next token as a finite number, or an error naming what it was for.
  private mutating func coordinate(
    _ name: String, of statement: String
  ) throws(SceneError) -> Double {
    guard let token = nextToken() else {
      throw SceneError(
        file: file, line: lastEnd.line, column: lastEnd.column,
        message: "expected \(name) of '\(statement)', found end of line")
    }
    return try number(token, name, of: statement)
  }

  private func number(
    _ token: Token, _ name: String, of statement: String
  ) throws(SceneError) -> Double {
    guard let value = DecimalParser.parse(slice(token.start, token.end)) else {
      throw error(
        at: token,
        "expected a number for \(name) of '\(statement)', found "
          + "'\(quote(token))'")
    }
    guard value.isFinite else {
      throw error(
        at: token,
        "expected a finite number for \(name) of '\(statement)', found "
          + "'\(quote(token))'")
    }
    return value
  }

  private mutating func endOfLine(after form: String) throws(SceneError) {
    if let extra = nextToken() {
      throw error(at: extra, "unexpected '\(quote(extra))' after '\(form)'")
    }
  }

  // MARK: Tokens

  /// The next token on this line, or nil at its end (a newline, a comment,
  /// or the end of the file), leaving `index` at the newline or the end.
  private mutating func nextToken() -> Token? {
    while index < bytes.count {
      let byte = bytes[index]
      if byte == UInt8(ascii: " ") || byte == UInt8(ascii: "\t") {
        index += 1
      } else if byte == UInt8(ascii: "\n") {
        return nil
      } else if byte == UInt8(ascii: "#") {
        while index < bytes.count && bytes[index] != UInt8(ascii: "\n") {
          index += 1
        }
        return nil
      } else if Self.isOtherBlank(byte) {
        index += 1
      } else if byte == UInt8(ascii: "\\"), let end = continuationEnd(index) {
        index = end
        newLine()
      } else {
        break
      }
    }
    guard index < bytes.count else { return nil }
    let start = index
    while index < bytes.count {
      let byte = bytes[index]
      if byte == UInt8(ascii: " ") || byte == UInt8(ascii: "\n")
        || byte == UInt8(ascii: "\t") || Self.isOtherBlank(byte)
      {
        break
      }
      if byte == UInt8(ascii: "\\") && continuationEnd(index) != nil { break }
      index += 1
    }
    let column = start - lineStart + 1
    lastEnd = (line, index - lineStart + 1)
    return Token(start: start, end: index, line: line, column: column)
  }

  /// Carriage return (CRLF files), vertical tab and form feed.
  private static func isOtherBlank(_ byte: UInt8) -> Bool {
    byte == 0x0D || byte == 0x0B || byte == 0x0C
  }

  /// When the `\` at `position` is followed by nothing but blanks before
  /// its line's end, the position just after that newline (or the file's
  /// end): the line continues there.
  private func continuationEnd(_ position: Int) -> Int? {
    var next = position + 1
    while next < bytes.count {
      let byte = bytes[next]
      if byte == UInt8(ascii: "\n") { return next + 1 }
      guard
        byte == UInt8(ascii: " ") || byte == UInt8(ascii: "\t")
          || Self.isOtherBlank(byte)
      else { return nil }
      next += 1
    }
    return next
  }

  private mutating func newLine() {
    line += 1
    lineStart = index
  }

  private mutating func skipRestOfLine() {
    while nextToken() != nil {}
  }

  private func slice(_ start: Int, _ end: Int) -> UnsafeBufferPointer<UInt8> {
    UnsafeBufferPointer(rebasing: bytes[start..<end])
  }

  // MARK: Messages

  private func error(at token: Token, _ message: String) -> SceneError {
    SceneError(
      file: file, line: token.line, column: token.column, message: message)
  }

  private func malformedFaceVertex(_ token: Token) -> SceneError {
    error(
      at: token,
      "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, found "
        + "'\(quote(token))'")
  }

  /// Names line elements and free-form geometry as valid OBJ this reader
  /// does not render; otherwise suggests the nearest keyword.
  private func unknown(_ keyword: Token) -> SceneError {
    let text = quote(keyword)
    let length = keyword.end - keyword.start
    let word =
      length <= Self.longestSuggestible
      ? String(decoding: slice(keyword.start, keyword.end), as: UTF8.self) : ""
    switch word {
    case "l", "p":
      return error(
        at: keyword,
        "'\(word)' (a \(word == "l" ? "line" : "point") element) is not "
          + "supported: only faces ('f') are read")
    case _ where Self.freeForm.contains(word):
      return error(
        at: keyword,
        "'\(word)' (free-form geometry) is not supported: only polygonal "
          + "faces ('f') are read")
    default:
      break
    }
    if DecimalParser.parse(slice(keyword.start, keyword.end)) != nil {
      return error(
        at: keyword, "expected a statement keyword, found the number \(text)")
    }
    if !word.isEmpty, let suggestion = nearest(to: word, in: Self.keywords) {
      return error(
        at: keyword,
        "expected a statement keyword, found '\(text)'; did you mean "
          + "'\(suggestion)'?")
    }
    return error(
      at: keyword,
      "expected a statement keyword "
        + "(\(Self.keywords.joined(separator: ", "))), found '\(text)'")
  }

  /// The token as messages quote it: cut to `longestQuoted` bytes, with
  /// control characters and line separators escaped (`\u{1B}`), so that the
  /// message stays on one line and cannot drive the terminal showing it.
  private func quote(_ token: Token) -> String {
    let length = token.end - token.start
    let shown = Swift.min(length, Self.longestQuoted)
    let raw = String(
      decoding: slice(token.start, token.start + shown), as: UTF8.self)
    var quoted = String.UnicodeScalarView()
    for scalar in raw.unicodeScalars {
      if scalar.value < 0x20 || (0x7F...0x9F).contains(scalar.value)
        || scalar.value == 0x2028 || scalar.value == 0x2029
      {
        let hex = String(scalar.value, radix: 16, uppercase: true)
        quoted.append(contentsOf: "\\u{\(hex)}".unicodeScalars)
      } else {
        quoted.append(scalar)
      }
    }
    return String(quoted) + (shown < length ? "…" : "")
  }
}
