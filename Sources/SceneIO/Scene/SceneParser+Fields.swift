import Geometry
import SceneDescription
import PlatformSupport

/// Fields, values and the counts blocks declare.
extension SceneParser {
  /// Reads `{ field value … }`, each of `fields` at most once, calling `read`
  /// to parse each value; returns the closing brace, for messages about
  /// missing fields.
  mutating func parseFields(
    _ block: String, _ fields: [StaticString],
    read: (inout SceneParser, String) throws(SceneError) -> Void
  ) throws(SceneError) -> SceneToken {
    try expect(.open, "'{' after \(block)")
    // A mask rather than an array: no block has more than a few fields,
    // and an allocation per block showed in the parse of large scenes.
    var seen: UInt64 = 0
    while true {
      let token = try next()
      switch token.kind {
      case .close:
        return token
      case .end, .open:
        throw unexpectedEnd(token, in: block)
      case .word:
        guard
          let index = fields.firstIndex(where: { tokenizer.matches(token, $0) })
        else {
          throw unexpected(
            token, expected: "a field of \(block)",
            choices: fields.map { "\($0)" })
        }
        guard seen & (1 << index) == 0 else {
          throw error(
            at: token, "'\(fields[index])' is given twice in \(block)")
        }
        seen |= 1 << index
        try read(&self, "\(fields[index])")
      }
    }
  }

  /// The next token; a word longer than `maximumWordLength` is an error.
  mutating func next() throws(SceneError) -> SceneToken {
    let token = tokenizer.next()
    let length = token.end - token.start
    guard token.kind != .word || length <= Self.maximumWordLength else {
      var head = token
      head.end = token.start + 24
      throw error(
        at: token,
        "a word of \(length) bytes ('\(text(head))…') is longer than the "
          + "limit of \(Self.maximumWordLength) bytes")
    }
    return token
  }

  /// The position of the next token, without consuming it: a copy of the
  /// tokenizer is cheap, since its bytes are shared.
  func peekStart() -> SceneToken {
    var copy = tokenizer
    return copy.next()
  }

  mutating func number() throws(SceneError) -> Double {
    try numberAndToken().value
  }

  mutating func numberAndToken() throws(SceneError) -> (
    value: Double, token: SceneToken
  ) {
    let token = try next()
    guard let value = tokenizer.number(token) else {
      throw error(at: token, "expected a number, found '\(text(token))'")
    }
    // A zero is refused only when written non-zero ("1e-400"): the text
    // is looked at then, and the check costs nothing for other numbers.
    guard options.precision.holds(value),
      value != 0
        || !NumberRange.writesNonZero(
          bytes: tokenizer.bytes[token.start..<token.end])
    else {
      let written = text(token)
      if !value.isFinite && !NumberRange.isDecimal(written) {
        throw error(at: token, "expected a finite number, found '\(written)'")
      }
      guard let problem = options.precision.rangeProblem(value, text: written)
      else {
        throw error(at: token, "expected a finite number, found '\(written)'")
      }
      throw error(at: token, problem).exceeding(options.precision)
    }
    return (value, token)
  }

  mutating func vector() throws(SceneError) -> Vector3<Double> {
    let x = try number()
    let y = try number()
    let z = try number()
    return Vector3(x, y, z)
  }

  mutating func nonZeroVector(_ field: String) throws(SceneError)
    -> Vector3<Double>
  {
    let start = peekStart()
    let value = try vector()
    guard value.maxMagnitude > 0 else {
      throw error(at: start, "'\(field)' must not be the zero vector")
    }
    return value
  }

  mutating func color(_ field: String) throws(SceneError) -> RGB<Double> {
    let start = peekStart()
    let value = try vector()
    guard value.x >= 0 && value.y >= 0 && value.z >= 0 else {
      throw error(at: start, "'\(field)' components must not be negative")
    }
    return value
  }

  mutating func positive(_ field: String) throws(SceneError) -> Double {
    let (value, token) = try numberAndToken()
    guard value > 0 else {
      throw error(
        at: token, "'\(field)' must be positive, found \(text(token))")
    }
    return value
  }

  mutating func nonNegative(_ field: String) throws(SceneError)
    -> Double
  {
    let token = peekStart()
    let value = try number()
    guard value >= 0 else {
      throw error(
        at: token, "'\(field)' must not be negative, found \(text(token))")
    }
    return value
  }

  /// The largest count or index a scene may write: far beyond any scene
  /// that fits in memory, and exact in the Double it is read as.
  static let largestWholeNumber = 999_999_999_999_999

  mutating func wholeNumber(_ field: String) throws(SceneError) -> Int {
    let token = peekStart()
    let value = try number()
    guard value >= 0, value == value.rounded() else {
      throw error(
        at: token, "'\(field)' must be a whole number ≥ 0, found \(text(token))"
      )
    }
    guard value <= Double(Self.largestWholeNumber) else {
      throw error(
        at: token,
        "'\(field)' must be at most \(Self.largestWholeNumber), found "
          + text(token))
    }
    return Int(value)
  }

  // MARK: - Counts

  mutating func count(
    _ field: StaticString, in block: String
  ) throws(SceneError) -> (value: Int, token: SceneToken) {
    let token = try next()
    guard tokenizer.matches(token, field) else {
      throw error(
        at: token,
        "expected '\(field)' at the start of \(block), found '\(text(token))'")
    }
    let valueToken = peekStart()
    return (try wholeNumber("\(field)"), valueToken)
  }

  /// A block that declares its count (`numLights 2`), then that many
  /// items, each one of `choices` read by `item`: the Lights and Materials
  /// blocks, with their errors for a wrong count, an unknown item and an
  /// early end.
  mutating func parseCountedBlock<Item>(
    _ block: String, count field: StaticString, noun: String,
    choices: [String],
    item: (inout SceneParser, String) throws(SceneError) -> Item
  ) throws(SceneError) -> [Item] {
    try expect(.open, "'{' after \(block)")
    let declared = try count(field, in: block)
    var items: [Item] = []
    while true {
      let token = try next()
      if token.kind == .close {
        try checkCount(items.count, declared, block, "\(field)", noun, token)
        return items
      }
      guard token.kind == .word else {
        throw unexpectedEnd(token, in: block)
      }
      let name = text(token)
      guard choices.contains(name) else {
        throw unexpected(token, expected: "a \(noun)", choices: choices)
      }
      if items.count == declared.value {
        throw tooMany(declared, block, "\(field)", noun, token)
      }
      items.append(try item(&self, name))
    }
  }

  func checkCount(
    _ found: Int, _ declared: (value: Int, token: SceneToken), _ block: String,
    _ field: String, _ noun: String, _ close: SceneToken
  ) throws(SceneError) {
    guard found == declared.value else {
      throw error(
        at: close,
        "\(block) has \(found) \(noun)\(found == 1 ? "" : "s") but \(field) "
          + "(line \(declared.token.line)) says \(declared.value)")
    }
  }

  func tooMany(
    _ declared: (value: Int, token: SceneToken), _ block: String,
    _ field: String, _ noun: String, _ token: SceneToken
  ) -> SceneError {
    error(
      at: token,
      "\(block) has more \(noun)s than \(field) (line \(declared.token.line)) "
        + "says (\(declared.value))")
  }
}
