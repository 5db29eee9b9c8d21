import Geometry
import SceneDescription
import PlatformSupport

/// The statements of an OBJ file: vertices, normals, texture coordinates
/// and faces.
extension OBJParser {
  // MARK: Statements

  mutating func statement(_ keyword: Token) throws(SceneError) {
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
  mutating func vertex(_ keyword: Token) throws(SceneError) {
    if readsPlainLines && plainVertex() { return }
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
  mutating func normal(_ keyword: Token) throws(SceneError) {
    // Normal indices are stored as Int32, as vertex indices are.
    guard mesh.normals.count < Int(Int32.max) else {
      throw error(
        at: keyword, "too many normals: at most \(Int32.max) are supported")
    }
    let x = try coordinate("the x coordinate", of: "vn")
    let y = try coordinate("the y coordinate", of: "vn")
    let z = try coordinate("the z coordinate", of: "vn")
    try endOfLine(after: "vn x y z")
    // A zero normal has no direction: interpolated alone it would shade
    // and draw NaN.
    guard x != 0 || y != 0 || z != 0 else {
      throw error(
        at: keyword,
        "a normal of zero length has no direction: 'vn' needs a component "
          + "other than zero")
    }
    mesh.normals.append(Vector3(x, y, z))
  }

  /// `vt u [v [w]]`: (u, v), v 0 when it is not given.
  mutating func textureCoordinate(_ keyword: Token) throws(SceneError) {
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
  mutating func face(_ keyword: Token) throws(SceneError) {
    if readsPlainLines && plainFace() { return }
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
          mesh.append(
            vertices: SIMD3(first.vertex, previous.vertex, reference.vertex),
            normals: first.normal < 0
              ? nil : SIMD3(first.normal, previous.normal, reference.normal),
            texture: first.texture < 0
              ? nil
              : SIMD3(first.texture, previous.texture, reference.texture))
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
  mutating func faceVertex(
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
    if speculative && form == .vertexTexture
      && mesh.textureCoordinates.isEmpty
    {
      // Texture or normal, by what the parts before define.
      throw malformedFaceVertex(token)
    }
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
  mutating func resolve(
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
    if speculative {
      // A negative index counts back from what the parts before define.
      guard written > 0 else { throw malformedFaceVertex(token) }
      let before = written - count
      switch element {
      case .vertex: needed.vertices = Swift.max(needed.vertices, before)
      case .normal: needed.normals = Swift.max(needed.normals, before)
      case .textureCoordinate:
        needed.textureCoordinates = Swift.max(
          needed.textureCoordinates, before)
      }
      return Int32(truncatingIfNeeded: written - 1)
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
  func defined(_ count: Int, _ element: Element) -> String {
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
  func integer(_ start: Int, _ end: Int) -> Int? {
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
}
