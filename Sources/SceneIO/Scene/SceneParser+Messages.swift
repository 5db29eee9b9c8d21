import Geometry
import SceneDescription
import PlatformSupport

/// Errors at tokens, quoted safely, and the nearest keyword to suggest.
extension SceneParser {
  /// The token as messages quote it and keywords are compared with it:
  /// control characters and line separators are escaped (`\u{1B}`), so that
  /// a message stays on one line and cannot drive the terminal showing it.
  func text(_ token: SceneToken) -> String {
    Self.escaped(tokenizer.text(of: token))
  }

  /// `raw` with control characters and line separators escaped.
  package static func escaped(_ raw: String) -> String {
    guard raw.unicodeScalars.contains(where: needsEscape) else { return raw }
    var escaped = String.UnicodeScalarView()
    for scalar in raw.unicodeScalars {
      if needsEscape(scalar) {
        let hex = String(scalar.value, radix: 16, uppercase: true)
        escaped.append(contentsOf: "\\u{\(hex)}".unicodeScalars)
      } else {
        escaped.append(scalar)
      }
    }
    return String(escaped)
  }

  /// C0 and C1 controls, DEL, and the Unicode line and paragraph separators.
  static func needsEscape(_ scalar: Unicode.Scalar) -> Bool {
    scalar.value < 0x20 || (0x7F...0x9F).contains(scalar.value)
      || scalar.value == 0x2028 || scalar.value == 0x2029
  }

  func error(at token: SceneToken, _ message: String) -> SceneError {
    SceneError(
      file: file, line: token.line, column: token.column, message: message)
  }

  mutating func expect(
    _ kind: SceneToken.Kind, _ what: String
  ) throws(SceneError) {
    let token = try next()
    guard token.kind == kind else {
      throw error(
        at: token,
        "expected \(what), found "
          + (token.kind == .end ? "end of file" : "'\(text(token))'")
      )
    }
  }

  func unexpectedEnd(_ token: SceneToken, in block: String)
    -> SceneError
  {
    token.kind == .end
      ? error(at: token, "unexpected end of file: \(block) is missing its '}'")
      : error(at: token, "unexpected '\(text(token))' in \(block)")
  }

  /// Names an unsupported block as such, otherwise suggests the nearest of
  /// `choices`.
  func unexpected(
    _ token: SceneToken, expected: String, choices: [String]
  ) -> SceneError {
    let word = text(token)
    if let instead = Self.unsupportedBlocks[word] {
      return error(
        at: token, "'\(word)' is not supported: raytrace's \(instead)")
    }
    if tokenizer.number(token) != nil {
      return error(at: token, "expected \(expected), found the number \(word)")
    }
    var message = "expected \(expected), found '\(word)'"
    // Suggested from the bytes as written: "Sph", NUL, "ere" is one edit
    // from `Sphere`, its escaped form `Sph\u{0}ere` five.
    if let suggestion = nearest(to: tokenizer.text(of: token), in: choices) {
      message += "; did you mean '\(suggestion)'?"
    } else {
      let quoted = choices.map { "'\($0)'" }.joined(separator: ", ")
      message += " (expected one of \(quoted))"
    }
    return error(at: token, message)
  }

  func missing(
    _ block: String, _ fields: [(String, Bool)], _ close: SceneToken
  ) -> SceneError {
    let absent = fields.filter { !$0.1 }.map { "'\($0.0)'" }
    return error(
      at: close, "\(block) is missing \(absent.joined(separator: " and "))")
  }
}

/// The choice within edit distance ⌈length/3⌉ of `word`, case ignored, if any.
func nearest(to word: String, in choices: [String]) -> String? {
  let lowered = Array(word.lowercased().utf8)
  var best: (choice: String, distance: Int)?
  for choice in choices {
    let distance = editDistance(lowered, Array(choice.lowercased().utf8))
    if distance <= max(1, (choice.utf8.count + 2) / 3),
      distance < (best?.distance ?? .max)
    {
      best = (choice, distance)
    }
  }
  return best?.choice
}

/// Levenshtein distance, two rows at a time.
func editDistance(_ a: [UInt8], _ b: [UInt8]) -> Int {
  if a.isEmpty { return b.count }
  var previous = Array(0...b.count)
  var current = previous
  for i in 1...a.count {
    current[0] = i
    for j in stride(from: 1, through: b.count, by: 1) {
      let substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)
      current[j] = min(substitution, previous[j] + 1, current[j - 1] + 1)
    }
    swap(&previous, &current)
  }
  return previous[b.count]
}
