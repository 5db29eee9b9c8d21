/// The help screen and usage line, laid out as the real package does: labels
/// indented 2, descriptions from column 26, wrapped to the screen width.
struct HelpGenerator {
  static let helpIndent = 2
  static let labelColumnWidth = 26
  /// The real package's width when standard output is not a terminal; help
  /// here always uses it unless given `columns`, so output is reproducible.
  static let defaultScreenWidth = 80

  struct Section {
    struct Element {
      var label: String
      var abstract = ""
      var discussion = ""

      func rendered(screenWidth: Int) -> String {
        let paddedLabel =
          String(repeating: " ", count: HelpGenerator.helpIndent) + label
        let wrappedAbstract = abstract.wrapped(
          to: screenWidth, wrappingIndent: HelpGenerator.labelColumnWidth)
        let renderedAbstract: String
        if abstract.isEmpty {
          renderedAbstract = ""
        } else if paddedLabel.count < HelpGenerator.labelColumnWidth {
          renderedAbstract = String(
            wrappedAbstract.dropFirst(paddedLabel.count))
        } else {
          renderedAbstract = "\n" + wrappedAbstract
        }
        let renderedDiscussion =
          discussion.isEmpty
          ? ""
          : discussion.wrapped(
            to: screenWidth, wrappingIndent: HelpGenerator.helpIndent * 4)
            + "\n"
        return paddedLabel + renderedAbstract + "\n" + renderedDiscussion
      }
    }

    var title: String
    var elements: [Element]

    func rendered(screenWidth: Int) -> String {
      guard !elements.isEmpty else { return "" }
      let rendered = elements.map { $0.rendered(screenWidth: screenWidth) }
      return title.uppercased() + ":\n" + rendered.joined()
    }
  }

  var commandStack: [ParsableCommand.Type]
  var abstract: String
  var usage: String
  var sections: [Section]

  init(commandStack: [ParsableCommand.Type], includeHidden: Bool = false) {
    self.commandStack = commandStack
    let command = commandStack.last ?? HelpCommand.self
    let configuration = command.configuration
    let definitions = ArgumentDefinition.collect(from: command.init()).filter {
      $0.help.visibility.isShown(includeHidden: includeHidden)
    }

    if let usage = configuration.usage {
      self.usage = usage
    } else {
      let toolName = commandStack.map { $0._commandName }.joined(separator: " ")
      var usage = Self.synopsis(toolName: toolName, definitions: definitions)
      if !configuration.subcommands.isEmpty {
        if usage.last != " " { usage += " " }
        usage += "<subcommand>"
      }
      self.usage = usage
    }

    var abstract = configuration.abstract
    if !configuration.discussion.isEmpty {
      if !abstract.isEmpty { abstract += "\n" }
      abstract += "\n" + configuration.discussion
    }
    self.abstract = abstract
    sections = Self.sections(
      commandStack: commandStack, configuration: configuration,
      definitions: definitions)
  }

  /// `raytrace render [<options>] [<scene>]`: every argument while there are
  /// at most 12, else the required and positional ones after `[<options>]`.
  static func synopsis(toolName: String, definitions: [ArgumentDefinition])
    -> String
  {
    var parts = definitions.flatMap(\.synopses)
    guard !parts.isEmpty else { return toolName }
    if parts.count > 12 {
      parts = definitions.filter { $0.isPositional || !$0.isOptional }.flatMap(
        \.synopses)
      guard !parts.isEmpty, parts.count <= 12 else {
        return "\(toolName) <options>"
      }
      return "\(toolName) [<options>] " + parts.joined(separator: " ")
    }
    return toolName + " " + parts.joined(separator: " ")
  }

  private static func sections(
    commandStack: [ParsableCommand.Type], configuration: CommandConfiguration,
    definitions: [ArgumentDefinition]
  ) -> [Section] {
    var positional = Section(title: "Arguments", elements: [])
    var titled: [Section] = []
    var options = Section(title: "Options", elements: [])

    for definition in definitions {
      let element = Section.Element(
        label: definition.helpLabel, abstract: definition.helpAbstract,
        discussion: definition.help.discussion)
      if !definition.groupTitle.isEmpty {
        if let index = titled.firstIndex(where: {
          $0.title == definition.groupTitle
        }) {
          titled[index].elements.append(element)
        } else {
          titled.append(
            Section(title: definition.groupTitle, elements: [element]))
        }
      } else if definition.isPositional {
        positional.elements.append(element)
      } else {
        options.elements.append(element)
      }
    }

    if commandStack.contains(where: { !$0.configuration.version.isEmpty }) {
      options.elements.append(
        Section.Element(label: "--version", abstract: "Show the version."))
    }
    let helpNames = commandStack.helpNames.partitioned
    if !helpNames.isEmpty {
      options.elements.append(
        Section.Element(
          label: helpNames.map(\.synopsisString).joined(separator: ", "),
          abstract: "Show help information."))
    }

    let subcommands = Section(
      title: "Subcommands",
      elements: configuration.subcommands.compactMap { subcommand in
        guard subcommand.configuration.shouldDisplay else { return nil }
        var label = subcommand._commandName
        for alias in subcommand.configuration.aliases {
          label += ", " + alias
        }
        if let defaultSubcommand = configuration.defaultSubcommand,
          subcommand == defaultSubcommand
        {
          label += " (default)"
        }
        return Section.Element(
          label: label, abstract: subcommand.configuration.abstract)
      })

    return [positional] + titled + [options, subcommands]
  }

  func usageMessage() -> String {
    guard !usage.isEmpty else { return "" }
    return "Usage: " + usage.hangingIndentingEachLine(by: 7)
  }

  func rendered(screenWidth: Int? = nil) -> String {
    let screenWidth = screenWidth ?? Self.defaultScreenWidth
    let renderedSections =
      sections
      .map { $0.rendered(screenWidth: screenWidth) }
      .filter { !$0.isEmpty }
      .joined(separator: "\n")
    let renderedAbstract =
      abstract.isEmpty
      ? "" : "OVERVIEW: \(abstract)".wrapped(to: screenWidth) + "\n\n"
    let renderedUsage =
      usage.isEmpty
      ? "" : "USAGE: " + usage.hangingIndentingEachLine(by: 7) + "\n\n"
    var subcommandHint = ""
    if sections.contains(where: {
      $0.title == "Subcommands" && !$0.elements.isEmpty
    }) {
      var names = commandStack.map { $0._commandName }
      names.insert("help", at: min(1, names.count))
      subcommandHint =
        """
          \n  See '\(names.joined(separator: " ")) <subcommand>' for detailed \
          help.
          """
    }
    return renderedAbstract + renderedUsage + renderedSections + subcommandHint
  }
}

extension ArgumentDefinition {
  /// The usage-line pieces: `[--threads <threads>]`, `[<scene>]`, and both
  /// names of an inverted flag.
  var synopses: [String] {
    let repeating = isRepeating ? " ..." : ""
    let pieces: [String]
    switch kind {
    case .positional:
      pieces = ["<\(valueName)>" + repeating]
    case .option:
      guard let name = names.preferredName else { return [] }
      pieces = ["\(name.synopsisString) <\(valueName)>" + repeating]
    case .flag:
      pieces = [names.preferredName, invertedNames.preferredName].compactMap {
        $0?.synopsisString
      }
    }
    return isOptional ? pieces.map { "[\($0)]" } : pieces
  }

  /// The left column: `-o, --output, -output <file>`, `--flag/--no-flag`.
  var helpLabel: String {
    switch kind {
    case .positional:
      return "<\(valueName)>"
    case .option:
      return names.partitioned.map(\.synopsisString).joined(separator: ", ")
        + " <\(valueName)>"
    case .flag:
      let on = names.partitioned.map(\.synopsisString).joined(separator: ", ")
      guard !invertedNames.isEmpty else { return on }
      return on + "/"
        + invertedNames.partitioned.map(\.synopsisString).joined(
          separator: ", ")
    }
  }

  /// The abstract followed by `(values: a, b; default: a)` where known.
  var helpAbstract: String {
    var notes: [String] = []
    if !allValues.isEmpty {
      notes.append("values: " + allValues.joined(separator: ", "))
    }
    if let defaultValueDescription, !defaultValueDescription.isEmpty {
      notes.append("default: " + defaultValueDescription)
    }
    let suffix = notes.isEmpty ? "" : "(" + notes.joined(separator: "; ") + ")"
    return [help.abstract, suffix].filter { !$0.isEmpty }.joined(separator: " ")
  }
}

// MARK: - Text

extension String {
  /// Wraps at spaces so that no line passes `columns`, indenting every
  /// non-empty line by `wrappingIndent`; existing line breaks stay. A word
  /// longer than the width stays whole on its own line.
  func wrapped(to columns: Int, wrappingIndent: Int = 0) -> String {
    let width = columns - wrappingIndent
    guard width > 0 else { return self }
    let paragraphs = split(separator: "\n", omittingEmptySubsequences: false)
    var lines: [Substring] = []
    for (number, paragraph) in paragraphs.enumerated() {
      let isLastParagraph = number == paragraphs.count - 1
      var rest = paragraph
      while true {
        // As in the real package, a line exactly `width` long is broken
        // unless nothing follows it.
        if rest.count < width || (rest.count == width && isLastParagraph) {
          lines.append(rest)
          break
        }
        let window = rest.prefix(width)
        if let space = window.lastIndex(of: " ") {
          lines.append(rest[..<space])
          rest = rest[rest.index(after: space)...]
        } else if let space = rest.firstIndex(of: " ") {
          lines.append(rest[..<space])
          rest = rest[rest.index(after: space)...]
        } else {
          lines.append(rest)
          break
        }
      }
    }
    let indent = String(repeating: " ", count: wrappingIndent)
    return lines.map { $0.isEmpty ? "" : indent + $0 }.joined(separator: "\n")
  }

  /// Indents every line but the first, for multi-line usage strings.
  func hangingIndentingEachLine(by count: Int) -> String {
    let lines = split(separator: "\n", omittingEmptySubsequences: false)
    guard let first = lines.first else { return self }
    let indent = String(repeating: " ", count: count)
    return
      ([String(first)]
      + lines.dropFirst().map { $0.isEmpty ? "" : indent + $0 })
      .joined(separator: "\n")
  }

  /// `pngLevel` → `png-level`, `myURLValue` → `my-url-value`: how property
  /// and type names become command-line names.
  func convertedToSnakeCase(separator: Character = "_") -> String {
    let characters = Array(self)
    var result = ""
    for (index, character) in characters.enumerated() {
      if character.isUppercase, index > 0, result.last != separator {
        let previous = characters[index - 1]
        let next = index + 1 < characters.count ? characters[index + 1] : nil
        let startsWord =
          previous.isLowercase || previous.isNumber
          || (previous.isUppercase && next?.isLowercase == true)
        if startsWord { result.append(separator) }
      }
      result += character.lowercased()
    }
    return result
  }

  /// The Levenshtein distance, for "Did you mean" suggestions.
  func editDistance(to other: String) -> Int {
    let source = Array(self)
    let target = Array(other)
    guard !source.isEmpty else { return target.count }
    guard !target.isEmpty else { return source.count }
    var previous = Array(0...target.count)
    var current = previous
    for i in 1...source.count {
      current[0] = i
      for j in 1...target.count {
        let substitution =
          previous[j - 1] + (source[i - 1] == target[j - 1] ? 0 : 1)
        current[j] = Swift.min(
          previous[j] + 1, current[j - 1] + 1, substitution)
      }
      swap(&previous, &current)
    }
    return previous[target.count]
  }
}
