import Geometry
import SceneDescription
import PlatformSupport

/// The depth check made before a property list is decoded: Foundation's
/// decoders recurse once per level of nesting, so a file of a few
/// megabytes nested a hundred thousand deep would overflow the stack.
extension PropertyList {
  /// Throws when `bytes` nest deeper than `maximumDepth`, when a binary
  /// list's object table is not one the depth can be read from or its
  /// shared references expand beyond `maximumVisits(forSize:)`, or when an
  /// XML list has a problem the scan finds (`xmlProblem`).
  static func check(_ bytes: [UInt8], file: String) throws(SceneError) {
    let tooDeep =
      "the property list is nested more than \(maximumDepth) levels deep"
    if bytes.starts(with: Array("bplist".utf8)) {
      let shape: (depth: Int, visits: Int)?
      switch binaryReading(bytes) {
      case .shape(let depth, let visits): shape = (depth, visits)
      case .unsupported(let reason):
        throw SceneError(
          file: file, line: 0, column: 0,
          message: "not a valid property list: \(reason)")
      case .malformed: shape = nil
      }
      switch shape {
      case .some(let shape) where shape.depth > maximumDepth:
        throw SceneError(file: file, line: 0, column: 0, message: tooDeep)
      case .some(let shape)
      where shape.visits > maximumVisits(forSize: bytes.count):
        throw SceneError(
          file: file, line: 0, column: 0,
          message: "the property list's shared objects would be read more "
            + "than \(maximumVisits(forSize: bytes.count)) times (each "
            + "reference to an object reads it again)")
      case .some: return
      case .none:
        throw SceneError(
          file: file, line: 0, column: 0,
          message: "not a valid property list: the binary object table is "
            + "malformed")
      }
    }
    var text = bytes
    if let encoding = bytes.withUnsafeBufferPointer(wideEncoding) {
      guard let utf8 = utf8(bytes, from: encoding) else {
        throw SceneError(
          file: file, line: 0, column: 0,
          message: "not a valid property list: its text is not valid in the "
            + "encoding its byte-order mark names")
      }
      text = utf8
    }
    if let problem = xmlProblem(text) {
      throw SceneError(
        file: file, line: problem.line, column: 0,
        message: problem.message.hasPrefix("the property list is nested")
          ? problem.message : "not a valid property list: \(problem.message)")
    }
  }

  /// The most objects a decode may visit, shared references counted each
  /// time they are reached: 16 per byte of the file and a thousand more,
  /// far above any list without sharing (each object takes at least a
  /// byte) and far below what sharing can make (2ⁿ from n objects).
  static func maximumVisits(forSize size: Int) -> Int {
    16 * size + 1000
  }

  /// What the check of a binary list finds.
  enum BinaryReading: Equatable {
    case shape(depth: Int, visits: Int)
    /// Well formed, but holding what no scene holds and Foundation's
    /// reader does not survive on Linux: a set, or a dictionary key that
    /// is not a string (bridging either to Swift crashed it).
    case unsupported(String)
    case malformed
  }

  /// The nesting depth of a binary property list (`bplist00`), 1 for a
  /// top object that holds no array, set or dictionary and more than
  /// `maximumDepth` for a list whose references form a cycle; and how many
  /// objects a decode visits, each reference to a shared object counted
  /// (saturating far above any limit). Malformed when its trailer or
  /// object table point outside the file; unsupported, with the reason, when
  /// it holds what no scene holds.
  ///
  /// Iterative, with each object's depth and visits computed once, so
  /// neither the file's nesting nor objects shared between containers cost
  /// stack or time beyond one visit of each reference; every size is
  /// checked before it is multiplied, so no count a file claims overflows.
  static func binaryReading(_ bytes: [UInt8]) -> BinaryReading {
    var unsupported: String?
    guard let shape = binaryShapeChecking(bytes, unsupported: &unsupported)
    else { return unsupported.map { .unsupported($0) } ?? .malformed }
    return .shape(depth: shape.depth, visits: shape.visits)
  }

  private static func binaryShapeChecking(
    _ bytes: [UInt8], unsupported: inout String?
  ) -> (depth: Int, visits: Int)? {
    let count = bytes.count
    guard count >= 8 + 32 else { return nil }
    func integer(_ offset: Int, _ size: Int) -> Int? {
      guard size >= 1, size <= 8, offset >= 0, offset <= count - size
      else { return nil }
      var value: UInt64 = 0
      for index in offset..<(offset + size) {
        value = value << 8 | UInt64(bytes[index])
      }
      return value <= UInt64(Int.max) ? Int(value) : nil
    }
    let trailer = count - 32
    let offsetSize = Int(bytes[trailer + 6])
    let referenceSize = Int(bytes[trailer + 7])
    guard let objects = integer(trailer + 8, 8),
      let top = integer(trailer + 16, 8),
      let table = integer(trailer + 24, 8),
      objects > 0, objects <= count, top < objects,
      table <= count, objects <= (count - table) / max(offsetSize, 1)
    else { return nil }
    /// The references an object holds: a container's elements (a
    /// dictionary's keys and values), none for anything else.
    func children(_ object: Int) -> [Int]? {
      guard let offset = integer(table + object * offsetSize, offsetSize),
        offset < count
      else { return nil }
      let marker = bytes[offset]
      let kind = marker >> 4
      if kind == 0xC {
        unsupported = "it holds a set, which no scene holds"
        return nil
      }
      guard kind == 0xA || kind == 0xD else { return [] }
      var length = Int(marker & 0x0F)
      var start = offset + 1
      if length == 0x0F {
        guard start < count, bytes[start] >> 4 == 0x1 else { return nil }
        let size = 1 << Int(bytes[start] & 0x0F)
        guard let value = integer(start + 1, size) else { return nil }
        length = value
        start += 1 + size
      }
      // A count the file cannot hold is refused before it is doubled.
      guard length <= count, start <= count else { return nil }
      let references = kind == 0xD ? 2 * length : length
      guard references <= (count - start) / max(referenceSize, 1)
      else { return nil }
      var result: [Int] = []
      result.reserveCapacity(references)
      for index in 0..<references {
        guard
          let reference = integer(
            start + index * referenceSize, referenceSize),
          reference < objects
        else { return nil }
        // A dictionary's keys (its first `length` references) are strings.
        if kind == 0xD && index < length {
          guard
            let keyOffset = integer(
              table + reference * offsetSize, offsetSize),
            keyOffset < count
          else { return nil }
          let keyKind = bytes[keyOffset] >> 4
          guard keyKind == 0x5 || keyKind == 0x6 else {
            unsupported = "a dictionary has a key that is not a string"
            return nil
          }
        }
        result.append(reference)
      }
      return result
    }
    // depth[o]: 0 unvisited, −1 on the current path, else its depth;
    // visits[o] the objects a decode of o reads, o itself included.
    let saturated = 1 << 60
    var depth = [Int](repeating: 0, count: objects)
    var visits = [Int](repeating: 0, count: objects)
    var stack:
      [(object: Int, children: [Int], next: Int, deepest: Int, visits: Int)] =
        []
    guard let first = children(top) else { return nil }
    stack.append((top, first, 0, 0, 1))
    depth[top] = -1
    let tooDeep = (maximumDepth + 1, 0)
    while var frame = stack.popLast() {
      if frame.next == frame.children.count {
        depth[frame.object] = frame.deepest + 1
        visits[frame.object] = frame.visits
        if var parent = stack.popLast() {
          parent.deepest = max(parent.deepest, frame.deepest + 1)
          parent.visits = min(saturated, parent.visits + frame.visits)
          stack.append(parent)
        }
        continue
      }
      let child = frame.children[frame.next]
      frame.next += 1
      switch depth[child] {
      case -1:
        return tooDeep
      case 0:
        guard stack.count < maximumDepth else { return tooDeep }
        guard let grandchildren = children(child) else { return nil }
        stack.append(frame)
        depth[child] = -1
        stack.append((child, grandchildren, 0, 0, 1))
      default:
        frame.deepest = max(frame.deepest, depth[child])
        frame.visits = min(saturated, frame.visits + visits[child])
        stack.append(frame)
      }
    }
    return (depth[top], visits[top])
  }
}
