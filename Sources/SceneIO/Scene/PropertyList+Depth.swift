import SceneModel

/// The depth check made before a property list is decoded: Foundation's
/// decoders recurse once per level of nesting, so a file of a few
/// megabytes nested a hundred thousand deep would overflow the stack.
extension PropertyList {
  /// Throws when `bytes` nest deeper than `maximumDepth`, or when a binary
  /// list's object table is not one the depth can be read from.
  static func checkDepth(_ bytes: [UInt8], file: String) throws(SceneError) {
    let tooDeep =
      "the property list is nested more than \(maximumDepth) levels deep"
    if bytes.starts(with: Array("bplist".utf8)) {
      switch binaryDepth(bytes) {
      case .some(let depth) where depth <= maximumDepth: return
      case .some:
        throw SceneError(file: file, line: 0, column: 0, message: tooDeep)
      case .none:
        throw SceneError(
          file: file, line: 0, column: 0,
          message: "not a valid property list: the binary object table is "
            + "malformed")
      }
    }
    if let line = xmlLineBeyondDepth(bytes) {
      throw SceneError(file: file, line: line, column: 0, message: tooDeep)
    }
  }

  /// The line of an XML property list at which its elements first nest
  /// deeper than `maximumDepth`, or nil. A conservative count of opening
  /// and closing `dict` and `array` tags; binary lists are not scanned.
  static func xmlLineBeyondDepth(_ bytes: [UInt8]) -> Int? {
    guard !bytes.starts(with: Array("bplist".utf8)) else { return nil }
    var depth = 0
    var line = 1
    var index = 0
    let count = bytes.count
    while index < count {
      let byte = bytes[index]
      if byte == 0x0A {
        line += 1
      } else if byte == UInt8(ascii: "<"), index + 1 < count {
        let closing = bytes[index + 1] == UInt8(ascii: "/")
        let nameStart = index + (closing ? 2 : 1)
        if starts(bytes, at: nameStart, with: "dict")
          || starts(bytes, at: nameStart, with: "array")
        {
          var end = nameStart
          while end < count && bytes[end] != UInt8(ascii: ">") { end += 1 }
          let selfClosing =
            end > 0 && end < count
            && bytes[end - 1] == UInt8(ascii: "/")
          if closing {
            depth -= 1
          } else if !selfClosing {
            depth += 1
            if depth > maximumDepth { return line }
          }
        }
      }
      index += 1
    }
    return nil
  }

  private static func starts(
    _ bytes: [UInt8], at index: Int, with word: StaticString
  ) -> Bool {
    let length = word.utf8CodeUnitCount
    guard index + length <= bytes.count else { return false }
    return word.withUTF8Buffer { word in
      for offset in 0..<length where bytes[index + offset] != word[offset] {
        return false
      }
      return true
    }
  }

  /// The nesting depth of a binary property list (`bplist00`): 1 for a
  /// top object that holds no array, set or dictionary, and more than
  /// `maximumDepth` for a list whose references form a cycle. Nil when its
  /// trailer or object table point outside the file.
  ///
  /// Iterative, with each object's depth computed once, so neither the
  /// file's nesting nor objects shared between containers cost stack or
  /// time beyond one visit of each reference.
  static func binaryDepth(_ bytes: [UInt8]) -> Int? {
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
      guard kind == 0xA || kind == 0xC || kind == 0xD else { return [] }
      var length = Int(marker & 0x0F)
      var start = offset + 1
      if length == 0x0F {
        guard start < count, bytes[start] >> 4 == 0x1 else { return nil }
        let size = 1 << Int(bytes[start] & 0x0F)
        guard let value = integer(start + 1, size) else { return nil }
        length = value
        start += 1 + size
      }
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
        result.append(reference)
      }
      return result
    }
    // depth[o]: 0 unvisited, −1 on the current path, else its depth.
    var depth = [Int](repeating: 0, count: objects)
    var stack: [(object: Int, children: [Int], next: Int, deepest: Int)] = []
    guard let first = children(top) else { return nil }
    stack.append((top, first, 0, 0))
    depth[top] = -1
    while var frame = stack.popLast() {
      if frame.next == frame.children.count {
        depth[frame.object] = frame.deepest + 1
        if var parent = stack.popLast() {
          parent.deepest = max(parent.deepest, frame.deepest + 1)
          stack.append(parent)
        }
        continue
      }
      let child = frame.children[frame.next]
      frame.next += 1
      switch depth[child] {
      case -1:
        return maximumDepth + 1
      case 0:
        guard stack.count < maximumDepth else { return maximumDepth + 1 }
        guard let grandchildren = children(child) else { return nil }
        stack.append(frame)
        depth[child] = -1
        stack.append((child, grandchildren, 0, 0))
      default:
        frame.deepest = max(frame.deepest, depth[child])
        stack.append(frame)
      }
    }
    return depth[top]
  }
}
