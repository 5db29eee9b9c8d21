/// The help text of one argument, option or flag.
public struct ArgumentHelp: Sendable, ExpressibleByStringInterpolation {
  /// The text beside the argument's names in help.
  public var abstract: String
  /// Text shown on the lines below the abstract.
  public var discussion: String
  /// The placeholder in `<…>` after the names; the first long name by default.
  public var valueName: String?
  public var visibility: ArgumentVisibility

  public init(
    _ abstract: String = "",
    discussion: String = "",
    valueName: String? = nil,
    visibility: ArgumentVisibility = .default
  ) {
    self.abstract = abstract
    self.discussion = discussion
    self.valueName = valueName
    self.visibility = visibility
  }

  public init(stringLiteral value: String) {
    self.init(value)
  }

  /// Parsed as usual but left out of help unless hidden help is asked for.
  public static var hidden: ArgumentHelp {
    ArgumentHelp(visibility: .hidden)
  }

  /// Parsed as usual but never shown.
  public static var `private`: ArgumentHelp {
    ArgumentHelp(visibility: .private)
  }

  var shouldDisplay: Bool {
    visibility == .default
  }
}

/// Whether help shows an argument.
public struct ArgumentVisibility: Hashable, Sendable {
  enum Level: Int, Hashable, Sendable {
    case `default`, hidden, `private`
  }

  var level: Level

  public static let `default` = ArgumentVisibility(level: .default)
  public static let hidden = ArgumentVisibility(level: .hidden)
  public static let `private` = ArgumentVisibility(level: .private)

  func isShown(includeHidden: Bool) -> Bool {
    switch level {
    case .default: return true
    case .hidden: return includeHidden
    case .private: return false
    }
  }
}

/// Shell completion for an argument's values. Accepted so that declarations
/// match the real package; this stand-in writes no completion scripts.
public struct CompletionKind: Sendable {
  enum Kind: Sendable {
    case `default`
    case file(extensions: [String])
    case directory
    case list([String])
    case shellCommand(String)
  }

  var kind: Kind

  public static var `default`: CompletionKind {
    CompletionKind(kind: .default)
  }

  public static func file(extensions: [String] = []) -> CompletionKind {
    CompletionKind(kind: .file(extensions: extensions))
  }

  public static var directory: CompletionKind {
    CompletionKind(kind: .directory)
  }

  public static func list(_ words: [String]) -> CompletionKind {
    CompletionKind(kind: .list(words))
  }

  public static func shellCommand(_ command: String) -> CompletionKind {
    CompletionKind(kind: .shellCommand(command))
  }
}
