import Geometry
import SceneDescription
import PlatformSupport

/// The bytes a UTF-8 file may start with to say it is UTF-8.
let utf8ByteOrderMark: [UInt8] = [0xEF, 0xBB, 0xBF]

/// One token of a scene file: a brace or a run of other non-blank bytes.
struct SceneToken {
  enum Kind { case word, open, close, end }
  var kind: Kind
  var start: Int
  var end: Int
  var line: Int
  var column: Int
}

/// Splits a scene file into tokens lazily, so that a million-sphere file is
/// never held as an array of tokens.
///
/// Tokens are separated by white space; `{` and `}` are tokens of their own
/// even when they touch a word; `#` starts a comment to the end of the line.
struct SceneTokenizer {
  /// Owns `bytes`: a tokenizer, and each copy of it, keeps them alive.
  let source: SceneBytes
  /// Read without the bounds checks and the closure of an array's
  /// `withUnsafeBufferPointer` on every token.
  let bytes: UnsafeBufferPointer<UInt8>
  private var index = 0
  private var line = 1
  private var lineStart = 0

  init(bytes: SceneBytes) {
    source = bytes
    self.bytes = bytes.buffer
    // A UTF-8 byte-order mark (editors on Windows write one) is not part
    // of the first line: columns count from after it.
    if self.bytes.starts(with: utf8ByteOrderMark) {
      index = utf8ByteOrderMark.count
      lineStart = index
    }
  }

  init(bytes: [UInt8]) {
    self.init(bytes: SceneBytes(bytes))
  }

  /// Where the next token is looked for: enough to resume there.
  struct Position: Equatable {
    var index: Int
    var line: Int
    var lineStart: Int
  }

  var position: Position {
    get { Position(index: index, line: line, lineStart: lineStart) }
    set {
      (index, line, lineStart) = (
        newValue.index, newValue.line, newValue.lineStart
      )
    }
  }

  mutating func next() -> SceneToken {
    skipBlanksAndComments()
    let start = index
    let column = start - lineStart + 1
    guard start < bytes.count else {
      return SceneToken(
        kind: .end, start: start, end: start, line: line, column: column)
    }
    switch bytes[start] {
    case UInt8(ascii: "{"):
      index += 1
      return SceneToken(
        kind: .open, start: start, end: index, line: line, column: column)
    case UInt8(ascii: "}"):
      index += 1
      return SceneToken(
        kind: .close, start: start, end: index, line: line, column: column)
    default:
      while index < bytes.count && !Self.endsWord(bytes[index]) {
        index += 1
      }
      return SceneToken(
        kind: .word, start: start, end: index, line: line, column: column)
    }
  }

  private mutating func skipBlanksAndComments() {
    while index < bytes.count {
      let byte = bytes[index]
      if byte == UInt8(ascii: "\n") {
        index += 1
        line += 1
        lineStart = index
      } else if Self.isBlank(byte) {
        index += 1
      } else if byte == UInt8(ascii: "#") {
        while index < bytes.count && bytes[index] != UInt8(ascii: "\n") {
          index += 1
        }
      } else {
        return
      }
    }
  }

  static func isBlank(_ byte: UInt8) -> Bool {
    byte == 0x20 || byte == 0x09 || byte == 0x0D || byte == 0x0B || byte == 0x0C
  }

  static func endsWord(_ byte: UInt8) -> Bool {
    isBlank(byte) || byte == UInt8(ascii: "\n") || byte == UInt8(ascii: "{")
      || byte == UInt8(ascii: "}") || byte == UInt8(ascii: "#")
  }

  /// The fields of a sphere as scene files write it, `{ center x y z
  /// radius r }` after its keyword, read in one pass that converts each
  /// number as it finds it; nil, with the position unchanged, for anything
  /// else, which the parser then reads token by token.
  ///
  /// What is read here reads the same token by token: the same tokens
  /// (blanks and line breaks between them; a `#` gives up), numbers only
  /// where `DecimalParser`'s fast path converts the whole word, which
  /// `number(_:)` converts with the same code, and no word longer than
  /// the parser accepts. Only the result is left to the caller to check.
  mutating func plainSphere() -> (center: Vector3<Double>, radius: Double)? {
    guard let base = bytes.baseAddress else { return nil }
    var cursor = Cursor(
      at: base + index, end: base + bytes.count, line: line,
      lineStart: base + lineStart)
    guard cursor.symbol(UInt8(ascii: "{")), cursor.keyword("center"),
      let x = cursor.number(), let y = cursor.number(),
      let z = cursor.number(), cursor.keyword("radius"),
      let radius = cursor.number(), cursor.symbol(UInt8(ascii: "}"))
    else { return nil }
    index = cursor.at - base
    line = cursor.line
    lineStart = cursor.lineStart - base
    return (Vector3(x, y, z), radius)
  }

  /// Where `plainSphere` has read to: each read skips the blanks and line
  /// breaks before its token, and tells whether the token is the one
  /// expected.
  private struct Cursor {
    var at: UnsafePointer<UInt8>
    let end: UnsafePointer<UInt8>
    var line: Int
    var lineStart: UnsafePointer<UInt8>

    /// Whether a token starts before `end`; false at a comment, which
    /// the tokenizer skips and this reading leaves to it.
    mutating func skipBlanks() -> Bool {
      while at < end {
        let byte = at.pointee
        if byte == UInt8(ascii: "\n") {
          at += 1
          line += 1
          lineStart = at
        } else if SceneTokenizer.isBlank(byte) {
          at += 1
        } else {
          return byte != UInt8(ascii: "#")
        }
      }
      return false
    }

    mutating func symbol(_ brace: UInt8) -> Bool {
      guard skipBlanks(), at.pointee == brace else { return false }
      at += 1
      return true
    }

    mutating func keyword(_ word: StaticString) -> Bool {
      let length = word.utf8CodeUnitCount
      guard skipBlanks(), end - at > length,
        SceneTokenizer.endsWord(at[length])
      else { return false }
      for offset in 0..<length where at[offset] != word.utf8Start[offset] {
        return false
      }
      at += length
      return true
    }

    mutating func number() -> Double? {
      guard skipBlanks(),
        case .fast(let value, let stop) = DecimalParser.prefix(
          from: at, to: end),
        stop < end, SceneTokenizer.endsWord(stop.pointee),
        stop - at <= SceneParser.maximumWordLength
      else { return nil }
      at = stop
      return value
    }
  }

  /// The token's text, for messages and the rare slow paths.
  func text(of token: SceneToken) -> String {
    switch token.kind {
    case .end: return "end of file"
    default:
      return String(decoding: bytes[token.start..<token.end], as: UTF8.self)
    }
  }

  /// Whether the token is exactly `keyword`, without building a String.
  func matches(_ token: SceneToken, _ keyword: StaticString) -> Bool {
    guard token.kind == .word,
      token.end - token.start == keyword.utf8CodeUnitCount
    else { return false }
    let pointer = keyword.utf8Start
    for offset in 0..<keyword.utf8CodeUnitCount
    where bytes[token.start + offset] != pointer[offset] {
      return false
    }
    return true
  }

  /// The token as a number, or nil if it is not one.
  func number(_ token: SceneToken) -> Double? {
    guard token.kind == .word else { return nil }
    return DecimalParser.parse(
      UnsafeBufferPointer(rebasing: bytes[token.start..<token.end]))
  }
}
