// The declarations the parser reads off a command.

// MARK: - Declarations

/// What the parser and the help screen know about one declared argument.
struct ArgumentDefinition {
  enum Kind {
    case option(ValueParsing)
    /// Nil exclusivity: a counting flag, where every use counts.
    case flag(FlagExclusivity?)
    case positional(PositionalParsing)
  }

  var kind: Kind
  /// Empty for a positional argument.
  var names: [Name]
  /// The names that turn a flag off.
  var invertedNames: [Name] = []
  /// The property's name without the wrapper's underscore.
  var key: String
  var help: ArgumentHelp
  var isRepeating: Bool
  /// Whether the command line may leave it out.
  var isOptional: Bool
  var defaultValueDescription: String?
  var allValues: [String]
  /// The heading of the option group it came from, if titled.
  var groupTitle = ""
  var sink: ArgumentSink

  var isPositional: Bool {
    if case .positional = kind { return true }
    return false
  }

  var isFlag: Bool {
    if case .flag = kind { return true }
    return false
  }

  var valueName: String {
    if let name = help.valueName, !name.isEmpty { return name }
    if !isPositional, let name = names.preferredName { return name.valueString }
    return key.convertedToSnakeCase(separator: "-")
  }

  /// The argument as its error messages name it: `--size <w h>` or `<scene>`.
  func label(for name: Name?) -> String {
    guard let name else { return "<\(valueName)>" }
    return "\(name.synopsisString) <\(valueName)>"
  }

  /// Every declared argument of `value`, in declaration order, option groups
  /// expanded in place.
  static func collect(from value: Any) -> [ArgumentDefinition] {
    Mirror(reflecting: value).children.flatMap {
      child -> [ArgumentDefinition] in
      guard let label = child.label,
        let declaring = child.value as? ArgumentDeclaring
      else {
        return []
      }
      let key = label.hasPrefix("_") ? String(label.dropFirst()) : label
      return declaring.definitions(key: key)
    }
  }

  /// Runs `validate()` of the option groups inside `value`, innermost first.
  static func validateGroups(in value: Any) throws {
    for child in Mirror(reflecting: value).children {
      try (child.value as? ArgumentDeclaring)?.validateNested()
    }
  }
}

/// How parsed tokens reach a wrapper's storage.
struct ArgumentSink {
  /// Reads one value token; false when it isn't a valid value.
  var take: (String) -> Bool = { _ in false }
  /// Records a flag's uses, `true` for a name and `false` for an inversion.
  var flag: ([Bool]) -> Void = { _ in }
  /// Moves the values read into the wrapper once the whole line has parsed.
  var commit: () -> Void
  /// Whether the wrapper has a value, parsed or default.
  var hasValue: () -> Bool
}
