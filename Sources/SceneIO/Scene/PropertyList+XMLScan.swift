import Geometry
import SceneDescription
import PlatformSupport

/// The scan of an XML property list made before it is decoded: its nesting
/// as the decoder will read it, and the first place where it is not a
/// property list the decoder can read, with the line it is on.
///
/// Foundation's decoder recurses once per level of nesting (so a file
/// nested a hundred thousand deep would overflow the stack), and its
/// messages name no line, or the wrong one. The scan reads the file as an
/// XML parser does: comments, CDATA sections, processing instructions and
/// the document type declaration hold no elements, whatever tags appear
/// inside them.
extension PropertyList {
  struct XMLProblem: Equatable {
    var line: Int
    var message: String
  }

  /// The elements a property list is made of.
  static let xmlElements: Set<String> = [
    "plist", "dict", "array", "key", "string", "integer", "real", "true",
    "false", "date", "data",
  ]

  /// The first problem of the XML property list `bytes` (UTF-8): nesting
  /// deeper than `maximumDepth`, a tag that is not a property list's, tags
  /// that do not match, an unclosed comment or section, an integer too
  /// large for any integer type or a real that is not a number; nil when
  /// none is found.
  static func xmlProblem(_ bytes: [UInt8]) -> XMLProblem? {
    var scanner = XMLScanner(bytes: bytes)
    return scanner.scan()
  }

  struct XMLScanner {
    let bytes: [UInt8]
    var index = 0
    var line = 1
    /// Open elements: name and line.
    var open: [(name: String, line: Int)] = []
    var depth = 0

    mutating func scan() -> XMLProblem? {
      let count = bytes.count
      while index < count {
        let byte = bytes[index]
        if byte == 0x0A {
          line += 1
          index += 1
          continue
        }
        guard byte == UInt8(ascii: "<") else {
          index += 1
          continue
        }
        let start = line
        if starts(with: "<!--") {
          guard skip(past: "-->") else {
            return XMLProblem(line: start, message: "a comment is never closed")
          }
        } else if starts(with: "<![CDATA[") {
          let textStart = index + 9
          guard skip(past: "]]>") else {
            return XMLProblem(
              line: start, message: "a CDATA section is never closed")
          }
          if let problem = checkValue(
            from: textStart, to: index - 3, line: start)
          {
            return problem
          }
        } else if starts(with: "<?") {
          guard skip(past: "?>") else {
            return XMLProblem(
              line: start, message: "a processing instruction is never closed")
          }
        } else if starts(with: "<!") {
          guard skipDeclaration() else {
            return XMLProblem(
              line: start, message: "a declaration is never closed")
          }
        } else if let problem = tag() {
          return problem
        }
      }
      if let last = open.last {
        return XMLProblem(
          line: last.line,
          message: "<\(last.name)> is never closed (the file ends first)")
      }
      return nil
    }

    func starts(with text: StaticString) -> Bool {
      let length = text.utf8CodeUnitCount
      guard index + length <= bytes.count else { return false }
      return text.withUTF8Buffer { text in
        for offset in 0..<length where bytes[index + offset] != text[offset] {
          return false
        }
        return true
      }
    }

    /// Moves past the next `end`, counting lines; false when there is none.
    mutating func skip(past end: StaticString) -> Bool {
      while index < bytes.count {
        if starts(with: end) {
          index += end.utf8CodeUnitCount
          return true
        }
        if bytes[index] == 0x0A { line += 1 }
        index += 1
      }
      return false
    }

    /// `<!DOCTYPE …>`, whose internal subset in brackets may hold `>`.
    mutating func skipDeclaration() -> Bool {
      var brackets = 0
      while index < bytes.count {
        switch bytes[index] {
        case 0x0A: line += 1
        case UInt8(ascii: "["): brackets += 1
        case UInt8(ascii: "]"): brackets -= 1
        case UInt8(ascii: ">") where brackets <= 0:
          index += 1
          return true
        default: break
        }
        index += 1
      }
      return false
    }

    /// A start, end or empty-element tag at `index`.
    mutating func tag() -> XMLProblem? {
      let start = line
      let slash = UInt8(ascii: "/")
      let closing = index + 1 < bytes.count && bytes[index + 1] == slash
      var end = index + (closing ? 2 : 1)
      let nameStart = end
      while end < bytes.count,
        !Self.endsName(bytes[end])
      {
        end += 1
      }
      let name = String(decoding: bytes[nameStart..<end], as: UTF8.self)
      // To the tag's end, past quoted attribute values.
      var quote: UInt8?
      while end < bytes.count {
        let byte = bytes[end]
        if byte == 0x0A { line += 1 }
        if let open = quote {
          if byte == open { quote = nil }
        } else if byte == UInt8(ascii: "\"") || byte == UInt8(ascii: "'") {
          quote = byte
        } else if byte == UInt8(ascii: ">") {
          break
        }
        end += 1
      }
      guard end < bytes.count else {
        return XMLProblem(
          line: start, message: "a tag is never closed with '>'")
      }
      let empty = !closing && end > nameStart && bytes[end - 1] == slash
      index = end + 1
      guard PropertyList.xmlElements.contains(name) else {
        return XMLProblem(
          line: start,
          message: "<\(closing ? "/" : "")\(SceneParser.escaped(name))> is not "
            + "an element of a property list")
      }
      let nests = name == "dict" || name == "array"
      if closing {
        guard let last = open.popLast() else {
          return XMLProblem(line: start, message: "</\(name)> closes nothing")
        }
        guard last.name == name else {
          return XMLProblem(
            line: start,
            message: "</\(name)> closes <\(last.name)> of line \(last.line)")
        }
        if nests { depth -= 1 }
        return nil
      }
      if empty { return nil }
      if nests {
        depth += 1
        if depth > PropertyList.maximumDepth {
          return XMLProblem(
            line: start,
            message: "the property list is nested more than "
              + "\(PropertyList.maximumDepth) levels deep")
        }
      }
      if name == "integer" || name == "real" {
        let textStart = index
        while index < bytes.count, bytes[index] != UInt8(ascii: "<") {
          if bytes[index] == 0x0A { line += 1 }
          index += 1
        }
        let text = String(
          decoding: bytes[textStart..<index], as: UTF8.self
        ).filter { !$0.isWhitespace }
        if let problem = Self.numberProblem(name, text, line: start) {
          return problem
        }
      }
      open.append((name, start))
      return nil
    }

    /// Values in CDATA are not checked: none of the scene's numbers is one.
    func checkValue(from: Int, to: Int, line: Int) -> XMLProblem? { nil }

    static func endsName(_ byte: UInt8) -> Bool {
      byte == UInt8(ascii: ">") || byte == UInt8(ascii: "/") || byte == 0x20
        || byte == 0x09 || byte == 0x0A || byte == 0x0D
    }

    /// Why the text of an `<integer>` or `<real>` is not one, or nil.
    static func numberProblem(_ element: String, _ text: String, line: Int)
      -> XMLProblem?
    {
      let escaped = SceneParser.escaped(String(text.prefix(40)))
      let shown = "<\(element)>\(escaped)</\(element)>"
      if element == "integer" {
        if Int64(text) != nil || UInt64(text) != nil { return nil }
        let digits = text.drop { $0 == "-" || $0 == "+" }
        if !digits.isEmpty, digits.allSatisfy(\.isNumber) {
          return XMLProblem(
            line: line,
            message: "\(shown) is too large for any integer type (64 bits)")
        }
        return XMLProblem(line: line, message: "\(shown) is not a whole number")
      }
      if Double(text) != nil
        || ["nan", "+infinity", "-infinity", "inf", "-inf"]
          .contains(text.lowercased())
      {
        return nil
      }
      return XMLProblem(line: line, message: "\(shown) is not a number")
    }
  }
}
