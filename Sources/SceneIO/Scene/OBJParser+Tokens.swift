import Geometry
import SceneDescription
import PlatformSupport

/// Numbers, tokens and messages of the OBJ reader.
extension OBJParser {
  // MARK: Numbers

  /// The next token as a finite number, or an error naming what it was for.
  mutating func coordinate(
    _ name: String, of statement: String
  ) throws(SceneError) -> Double {
    guard let token = nextToken() else {
      throw SceneError(
        file: file, line: lastEnd.line, column: lastEnd.column,
        message: "expected \(name) of '\(statement)', found end of line")
    }
    return try number(token, name, of: statement)
  }

  func number(
    _ token: Token, _ name: String, of statement: String
  ) throws(SceneError) -> Double {
    guard let value = DecimalParser.parse(slice(token.start, token.end)) else {
      throw error(
        at: token,
        "expected a number for \(name) of '\(statement)', found "
          + "'\(quote(token))'")
    }
    if !precision.holds(value) || value == 0,
      NumberRange.isDecimal(quote(token)),
      let problem = precision.rangeProblem(value, text: quote(token))
    {
      throw error(at: token, "\(name) of '\(statement)': \(problem)")
        .exceeding(precision)
    }
    guard value.isFinite else {
      throw error(
        at: token,
        "expected a finite number for \(name) of '\(statement)', found "
          + "'\(quote(token))'")
    }
    return value
  }

  mutating func endOfLine(after form: String) throws(SceneError) {
    if let extra = nextToken() {
      throw error(at: extra, "unexpected '\(quote(extra))' after '\(form)'")
    }
  }

  // MARK: Tokens

  /// The next token on this line, or nil at its end (a newline, a comment,
  /// or the end of the file), leaving `index` at the newline or the end.
  mutating func nextToken() -> Token? {
    while index < bytes.count {
      let byte = bytes[index]
      if Self.isBlank(byte) {
        index += 1
      } else if byte == UInt8(ascii: "\n") {
        return nil
      } else if byte == UInt8(ascii: "#") {
        while index < bytes.count && bytes[index] != UInt8(ascii: "\n") {
          index += 1
        }
        return nil
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
      if Self.isBlank(byte) || byte == UInt8(ascii: "\n") {
        break
      }
      if byte == UInt8(ascii: "\\") && continuationEnd(index) != nil { break }
      index += 1
    }
    let column = start - lineStart + 1
    lastEnd = (line, index - lineStart + 1)
    return Token(start: start, end: index, line: line, column: column)
  }

  /// Whether `byte` separates tokens on a line: a space, a tab or one of
  /// `isOtherBlank`'s.
  @inline(__always)
  static func isBlank(_ byte: UInt8) -> Bool {
    byte == UInt8(ascii: " ") || byte == UInt8(ascii: "\t")
      || isOtherBlank(byte)
  }

  /// Carriage return (CRLF files), vertical tab and form feed.
  static func isOtherBlank(_ byte: UInt8) -> Bool {
    byte == 0x0D || byte == 0x0B || byte == 0x0C
  }

  /// When the `\` at `position` is followed by nothing but blanks before
  /// its line's end, the position just after that newline (or the file's
  /// end): the line continues there.
  func continuationEnd(_ position: Int) -> Int? {
    var next = position + 1
    while next < bytes.count {
      let byte = bytes[next]
      if byte == UInt8(ascii: "\n") { return next + 1 }
      guard Self.isBlank(byte) else { return nil }
      next += 1
    }
    return next
  }

  mutating func newLine() {
    line += 1
    lineStart = index
  }

  mutating func skipRestOfLine() {
    while nextToken() != nil {}
  }

  func slice(_ start: Int, _ end: Int) -> UnsafeBufferPointer<UInt8> {
    UnsafeBufferPointer(rebasing: bytes[start..<end])
  }

  // MARK: Messages

  func error(at token: Token, _ message: String) -> SceneError {
    SceneError(
      file: file, line: token.line, column: token.column, message: message)
  }

  func malformedFaceVertex(_ token: Token) -> SceneError {
    error(
      at: token,
      "expected a face vertex of the form v, v/vt, v//vn or v/vt/vn, found "
        + "'\(quote(token))'")
  }

  /// Names line elements and free-form geometry as valid OBJ this reader
  /// does not render; otherwise suggests the nearest keyword.
  func unknown(_ keyword: Token) -> SceneError {
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
  func quote(_ token: Token) -> String {
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
