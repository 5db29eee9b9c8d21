// Parsing: the reading of one command's tokens into its declarations
// (ArgumentDefinition.swift); the descent through subcommands is in
// CommandParser.swift.

// MARK: - One command's tokens

/// Reads one command's tokens into the wrappers behind its definitions.
struct ArgumentReader {
  let definitions: [ArgumentDefinition]
  private var longNames: [String: Match] = [:]
  private var singleDashNames: [String: Match] = [:]
  private var shortNames: [Character: Match] = [:]

  /// A declared name found in a token.
  struct Match {
    var index: Int
    var name: Name
    /// False for a flag's inverted name.
    var isOn: Bool
  }

  enum Token {
    case terminator
    case value
    case option(Match, attached: String?)
    /// Several short flags in one token, `-vx`; only the last may take a value.
    case shortGroup([Match])
    case unknown(Name)
  }

  init(_ definitions: [ArgumentDefinition]) {
    self.definitions = definitions
    for (index, definition) in definitions.enumerated() {
      for name in definition.names {
        register(Match(index: index, name: name, isOn: true))
      }
      for name in definition.invertedNames {
        register(Match(index: index, name: name, isOn: false))
      }
    }
  }

  private mutating func register(_ match: Match) {
    switch match.name {
    case .long(let text):
      longNames[text] = longNames[text] ?? match
    case .longWithSingleDash(let text):
      singleDashNames[text] = singleDashNames[text] ?? match
    case .short(let char, _):
      shortNames[char] = shortNames[char] ?? match
    }
  }

  private func takesValue(_ match: Match) -> Bool {
    !definitions[match.index].isFlag
  }

  /// A whole single-dash token: `-depth` is a name of its own, distinct from
  /// `--depth`, and `-o` a short name.
  private func singleDashMatch(_ body: Substring) -> Match? {
    if let match = singleDashNames[String(body)] { return match }
    if body.count == 1, let char = body.first { return shortNames[char] }
    return nil
  }

  func classify(_ token: String) -> Token {
    if token == "--" { return .terminator }
    if token.hasPrefix("--") {
      let body = token.dropFirst(2)
      let name = body.prefix { $0 != "=" }
      let attached =
        name.endIndex < body.endIndex
        ? String(body[body.index(after: name.endIndex)...]) : nil
      if let match = longNames[String(name)] {
        return .option(match, attached: attached)
      }
      return .unknown(.long(String(name)))
    }
    guard token.hasPrefix("-"), token.count > 1 else { return .value }
    let body = token.dropFirst()
    if let match = singleDashMatch(body) {
      return .option(match, attached: nil)
    }
    if let equals = body.firstIndex(of: "="),
      let match = singleDashMatch(body[..<equals])
    {
      return .option(
        match, attached: String(body[body.index(after: equals)...]))
    }
    if let first = body.first, let match = shortNames[first],
      case .short(_, true) = match.name,
      takesValue(match)
    {
      return .option(match, attached: String(body.dropFirst()))
    }
    let group = body.compactMap { shortNames[$0] }
    if group.count == body.count,
      group.dropLast().allSatisfy({ !takesValue($0) })
    {
      return .shortGroup(group)
    }
    if body.count == 1, let char = body.first {
      return .unknown(.short(char, allowingJoined: false))
    }
    return .unknown(.longWithSingleDash(String(body)))
  }

  private func isValue(_ token: String) -> Bool {
    if case .value = classify(token) { return true }
    return false
  }

  /// How many leading tokens are this command's own options, for a command
  /// that has subcommands: its options come before the subcommand's name.
  func leadingOptionCount(_ tokens: [String]) -> Int {
    var index = 0
    while index < tokens.count {
      let last: Match
      let attached: String?
      switch classify(tokens[index]) {
      case .option(let match, let value):
        (last, attached) = (match, value)
      case .shortGroup(let group):
        guard let final = group.last else { return index }
        (last, attached) = (final, nil)
      default:
        return index
      }
      index += 1
      guard case .option(let parsing) = definitions[last.index].kind else {
        continue
      }
      switch parsing {
      case .next, .unconditional, .scanningForValue:
        if attached == nil, index < tokens.count { index += 1 }
      case .upToNextOption:
        while index < tokens.count, isValue(tokens[index]) { index += 1 }
      case .remaining:
        index = tokens.count
      }
    }
    return index
  }

  /// What reading a command's tokens found wrong after the values were
  /// stored, in the real package's order: a missing required argument
  /// (reported before the command's `validate()`, unless help was asked
  /// for) and then an unknown option or unexpected argument (reported after
  /// `validate()` and after the help flags).
  struct Outcome {
    var missing: ParseFailure?
    var leftover: ParseFailure?
  }

  /// Parses `tokens` into the wrappers; throws a `ParseFailure` for a
  /// missing or invalid value, which the real package reports at once.
  func read(_ tokens: [String]) throws -> Outcome {
    var reading = Reading(reader: self, tokens: tokens)
    try reading.scan()
    return try reading.finish()
  }

  /// The state of one pass over the tokens.
  private struct Reading {
    let reader: ArgumentReader
    let tokens: [String]
    var definitions: [ArgumentDefinition] { reader.definitions }

    /// Tokens taken ahead of the scan by `.scanningForValue`.
    var taken: Set<Int> = []
    var values: [(token: Int, definition: Int, name: Name?, text: String)] = []
    var flagUses: [Int: [(isOn: Bool, text: String)]] = [:]
    var loose: [(token: Int, text: String, afterTerminator: Bool)] = []
    var unknown: [(token: Int, name: Name)] = []

    init(reader: ArgumentReader, tokens: [String]) {
      self.reader = reader
      self.tokens = tokens
    }

    mutating func scan() throws {
      var index = 0
      var afterTerminator = false
      while index < tokens.count {
        defer { index += 1 }
        if taken.contains(index) { continue }
        let token = tokens[index]
        if afterTerminator {
          loose.append((index, token, true))
          continue
        }
        switch reader.classify(token) {
        case .terminator:
          afterTerminator = true
        case .value:
          loose.append((index, token, false))
        case .unknown(let name):
          unknown.append((index, name))
        case .option(let match, let attached):
          try use(match, attached: attached, at: &index)
        case .shortGroup(let group):
          for match in group {
            try use(match, attached: nil, at: &index)
          }
        }
      }
    }

    /// Records one use of a name at `index`, taking the values it needs and
    /// moving `index` to the last token taken.
    private mutating func use(
      _ match: Match, attached: String?, at index: inout Int
    ) throws {
      let definition = definitions[match.index]
      guard case .option(let parsing) = definition.kind else {
        if let attached {
          throw ParseFailure(
            "The option '\(match.name.synopsisString)' does not take any "
              + "value, "
              + "but '\(attached)' was specified.")
        }
        flagUses[match.index, default: []].append((match.isOn, tokens[index]))
        return
      }
      let start = index
      var count = 0
      func record(_ text: String, at token: Int) {
        values.append((token, match.index, match.name, text))
        count += 1
      }
      if let attached {
        record(attached, at: start)
      }
      switch parsing {
      case .next:
        if attached == nil, index + 1 < tokens.count,
          !taken.contains(index + 1),
          reader.isValue(tokens[index + 1])
        {
          index += 1
          record(tokens[index], at: index)
        }
      case .unconditional:
        if attached == nil, index + 1 < tokens.count {
          index += 1
          record(tokens[index], at: index)
        }
      case .scanningForValue:
        if attached == nil {
          var next = index + 1
          while next < tokens.count, tokens[next] != "--" {
            if !taken.contains(next), reader.isValue(tokens[next]) {
              taken.insert(next)
              record(tokens[next], at: next)
              break
            }
            next += 1
          }
        }
      case .upToNextOption:
        while index + 1 < tokens.count, !taken.contains(index + 1),
          reader.isValue(tokens[index + 1])
        {
          index += 1
          record(tokens[index], at: index)
        }
      case .remaining:
        while index + 1 < tokens.count {
          index += 1
          record(tokens[index], at: index)
        }
      }
      if count == 0, parsing != .remaining {
        throw ParseFailure(
          "Missing value for '\(definition.label(for: match.name))'",
          help: helpLine(definition, name: match.name))
      }
    }

    /// Hands out positional values, then stores everything, in the real
    /// package's order of complaints.
    mutating func finish() throws -> Outcome {
      assignPositionals()

      for value in values.sorted(by: { $0.token < $1.token }) {
        let definition = definitions[value.definition]
        guard definition.sink.take(value.text) else {
          throw ParseFailure(
            "The value '\(value.text)' is invalid for "
              + "'\(definition.label(for: value.name))'"
              + choices(definition.allValues),
            help: helpLine(definition, name: value.name))
        }
      }

      for (index, uses) in flagUses.sorted(by: { $0.key < $1.key }) {
        guard case .flag(let exclusivity) = definitions[index].kind else {
          continue
        }
        switch exclusivity?.base {
        case .exclusive?:
          if uses.count > 1 {
            throw ParseFailure(
              "Value to be set with flag '\(uses[1].text)' "
                + "had already been set with flag '\(uses[0].text)'")
          }
          definitions[index].sink.flag(uses.map(\.isOn))
        case .chooseFirst?:
          definitions[index].sink.flag(uses.prefix(1).map(\.isOn))
        case .chooseLast?:
          definitions[index].sink.flag(uses.suffix(1).map(\.isOn))
        case nil:
          definitions[index].sink.flag(uses.map(\.isOn))
        }
      }

      for definition in definitions {
        definition.sink.commit()
      }

      var outcome = Outcome()
      outcome.missing = definitions.first { !$0.sink.hasValue() }.map {
        missingArgument($0)
      }
      if let first = unknown.first {
        outcome.leftover = ParseFailure(unknownOptionMessage(first.name))
      } else if loose.count == 1 {
        outcome.leftover = ParseFailure(
          "Unexpected argument '\(loose[0].text)'")
      } else if loose.count > 1 {
        let list = loose.map(\.text).joined(separator: "', '")
        outcome.leftover = ParseFailure(
          "\(loose.count) unexpected arguments: '\(list)'")
      }
      return outcome
    }

    /// Fills positional arguments in declaration order from the loose values,
    /// leaving in `loose` only what nothing took.
    private mutating func assignPositionals() {
      let positionals = definitions.indices.compactMap {
        index -> (Int, PositionalParsing)? in
        guard case .positional(let parsing) = definitions[index].kind else {
          return nil
        }
        return (index, parsing)
      }
      let hasPostTerminator = positionals.contains { $0.1 == .postTerminator }
      var queue = loose.filter { !(hasPostTerminator && $0.afterTerminator) }
      var afterTerminator =
        hasPostTerminator ? loose.filter(\.afterTerminator) : []
      for (index, parsing) in positionals {
        let taken: [(token: Int, text: String)]
        switch parsing {
        case .single:
          guard !queue.isEmpty else { continue }
          let first = queue.removeFirst()
          taken = [(first.token, first.text)]
        case .remaining:
          taken = queue.map { ($0.token, $0.text) }
          queue = []
        case .postTerminator:
          taken = afterTerminator.map { ($0.token, $0.text) }
          afterTerminator = []
        case .allUnrecognized:
          taken =
            (queue.map { ($0.token, $0.text) }
            + unknown.map { ($0.token, tokens[$0.token]) })
            .sorted { $0.token < $1.token }
          queue = []
          unknown = []
        }
        for value in taken {
          values.append((value.token, index, nil, value.text))
        }
      }
      loose = (queue + afterTerminator).sorted { $0.token < $1.token }
    }

    private func helpLine(_ definition: ArgumentDefinition, name: Name?)
      -> String
    {
      guard !definition.help.abstract.isEmpty else { return "" }
      return "\(definition.label(for: name))  \(definition.help.abstract)"
    }

    private func choices(_ values: [String]) -> String {
      guard !values.isEmpty else { return "" }
      if values.count < 6 {
        let quoted = values.map { "'\($0)'" }
        let list =
          quoted.count <= 2
          ? quoted.joined(separator: " and ")
          : quoted.dropLast().joined(separator: ", ") + " or "
            + (quoted.last ?? "")
        return ". Please provide one of \(list)."
      }
      return ". Please provide one of the following:\n"
        + values.map { "  - \($0)" }.joined(separator: "\n")
    }

    /// Suggests the closest declared long name within an edit distance of 3;
    /// short names get no suggestion.
    private func unknownOptionMessage(_ name: Name) -> String {
      let message = "Unknown option '\(name.synopsisString)'"
      guard !name.isShort else { return message }
      let typed = name.synopsisString
      var best: (distance: Int, text: String)?
      for definition in definitions {
        for candidate in definition.names + definition.invertedNames
        where !candidate.isShort {
          let distance = candidate.synopsisString.editDistance(to: typed)
          if distance < 4, distance < (best?.distance ?? Int.max) {
            best = (distance, candidate.synopsisString)
          }
        }
      }
      guard let best else { return message }
      return message + ". Did you mean '\(best.text)'?"
    }

    private func missingArgument(_ definition: ArgumentDefinition)
      -> ParseFailure
    {
      let repeating = definition.isRepeating ? " ..." : ""
      switch definition.kind {
      case .flag:
        let names = (definition.names + definition.invertedNames).map(
          \.synopsisString)
        if names.count == 1 {
          return ParseFailure("Missing expected argument '\(names[0])'")
        }
        return ParseFailure(
          "Missing one of: '\(names.joined(separator: "', '"))'")
      case .option:
        let label = definition.label(for: definition.names.preferredName)
        return ParseFailure(
          "Missing expected argument '\(label)\(repeating)'",
          help: helpLine(definition, name: definition.names.first))
      case .positional:
        return ParseFailure(
          "Missing expected argument "
            + "'\(definition.label(for: nil))\(repeating)'",
          help: helpLine(definition, name: nil))
      }
    }
  }
}
