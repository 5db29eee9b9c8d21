import Geometry

/// The common lines of a large mesh, `v 0.5 1 -2` and `f 1 2 3`, each read
/// in one pass over its bytes; any other line is left to the statements'
/// token-by-token reading, with its checks and messages (`vertex`, `face`).
/// Token by token, a vertex had cost about 170 ns and a triangle 150 ns:
/// most of a large mesh's parse.
extension OBJParser {
  /// `position` moved past blanks, to the next token, the line's end or
  /// the file's.
  @inline(__always)
  func skippingBlanks(_ position: Int) -> Int {
    var position = position
    while position < bytes.count && Self.isBlank(bytes[position]) {
      position += 1
    }
    return position
  }

  /// Reads a vertex of three numbers, `v x y z`, each of which the decimal
  /// fast path converts (`DecimalParser`, so finite and correctly rounded)
  /// and the precision holds, and nothing else on its line; false, with
  /// nothing read or changed, for any other: `vertex` then reads it.
  mutating func plainVertex() -> Bool {
    guard mesh.vertices.count < Int(Int32.max), let base = bytes.baseAddress
    else { return false }
    var position = index
    var tokenEnd = index
    var values: (Double, Double, Double) = (0, 0, 0)
    for k in 0..<3 {
      position = skippingBlanks(position)
      tokenEnd = position
      while tokenEnd < bytes.count && !Self.isBlank(bytes[tokenEnd])
        && bytes[tokenEnd] != UInt8(ascii: "\n")
      {
        tokenEnd += 1
      }
      guard tokenEnd > position,
        case .fast(let value, let stop) = DecimalParser.prefix(
          from: base + position, to: base + tokenEnd),
        // Always held: the fast path's values lie within 10^±22 of 1
        // or are 0, inside Float's normal range; checked as `number`
        // checks, should that path ever widen.
        stop == base + tokenEnd, precision.holds(value)
      else { return false }
      switch k {
      case 0: values.0 = value
      case 1: values.1 = value
      default: values.2 = value
      }
      position = tokenEnd
    }
    position = skippingBlanks(position)
    guard position == bytes.count || bytes[position] == UInt8(ascii: "\n")
    else { return false }
    mesh.vertices.append(Vector3(values.0, values.1, values.2))
    index = position
    lastEnd = (line, tokenEnd - lineStart + 1)
    return true
  }

  /// The most corners a face read by `plainFace` may have.
  static let plainFaceCorners = 8

  /// Reads a face of 3 to `plainFaceCorners` plain positive vertex indices
  /// (`f 1 2 3`), each a run of digits between blanks, in one pass over
  /// its line, and fans it into triangles as `face` would; false, with
  /// nothing read or changed, for any other face (slashes, signs, a
  /// comment, a line continuation, an index out of range or past Int32):
  /// `face` then reads it token by token, with its checks and messages.
  mutating func plainFace() -> Bool {
    var corners: (Int32, Int32, Int32, Int32, Int32, Int32, Int32, Int32) = (
      0, 0, 0, 0, 0, 0, 0, 0
    )
    var count = 0
    var largest = 0
    let vertexCount = mesh.vertices.count
    var position = index
    var tokenEnd = index
    let end = bytes.count
    while true {
      position = skippingBlanks(position)
      if position == end || bytes[position] == UInt8(ascii: "\n") { break }
      var value = 0
      let start = position
      while position < end {
        let digit = bytes[position] &- UInt8(ascii: "0")
        guard digit < 10 else { break }
        value = value * 10 + Int(digit)
        guard value <= Int(Int32.max) else { return false }
        position += 1
      }
      // Digits only, then a blank, the line's end or the file's.
      guard position > start, count < Self.plainFaceCorners else {
        return false
      }
      if position < end {
        let byte = bytes[position]
        guard Self.isBlank(byte) || byte == UInt8(ascii: "\n") else {
          return false
        }
      }
      // An index the sequential parse would refuse (0, or past the
      // vertices so far) is left to `face`, which names it.
      guard value >= 1, speculative || value <= vertexCount else {
        return false
      }
      largest = Swift.max(largest, value)
      withUnsafeMutableBytes(of: &corners) {
        $0.storeBytes(
          of: Int32(value), toByteOffset: 4 * count, as: Int32.self)
      }
      count += 1
      tokenEnd = position
    }
    guard count >= 3 else { return false }
    if speculative {
      // Each index names an element that the parts before must define.
      needed.vertices = Swift.max(needed.vertices, largest - vertexCount)
    }
    withUnsafeBytes(of: corners) { corners in
      func corner(_ k: Int) -> Int32 {
        corners.load(fromByteOffset: 4 * k, as: Int32.self) - 1
      }
      for third in 2..<count {
        mesh.append(
          vertices: SIMD3(corner(0), corner(third - 1), corner(third)),
          normals: nil, texture: nil)
      }
    }
    index = position
    lastEnd = (line, tokenEnd - lineStart + 1)
    return true
  }
}
