/// The names an option or flag answers to on the command line.
public struct NameSpecification: ExpressibleByArrayLiteral, Sendable {
  /// One way of naming, resolved against the property's name.
  public struct Element: Hashable, Sendable {
    enum Representation: Hashable, Sendable {
      case long
      case customLong(String, withSingleDash: Bool)
      case short
      case customShort(Character, allowingJoined: Bool)
    }

    var base: Representation

    /// `--` and the property's name in kebab case: `pngLevel` gives
    /// `--png-level`.
    public static var long: Element {
      Element(base: .long)
    }

    /// `--name`, or `-name` with `withSingleDash`; a single-dash name is a
    /// whole token, never a bundle of short flags.
    public static func customLong(_ name: String, withSingleDash: Bool = false)
      -> Element
    {
      Element(base: .customLong(name, withSingleDash: withSingleDash))
    }

    /// `-` and the property name's first letter.
    public static var short: Element {
      Element(base: .short)
    }

    /// `-c`; with `allowingJoined`, `-cvalue` also gives the value.
    public static func customShort(
      _ char: Character, allowingJoined: Bool = false
    ) -> Element {
      Element(base: .customShort(char, allowingJoined: allowingJoined))
    }
  }

  var elements: [Element]

  public init<S: Sequence>(_ sequence: S) where S.Element == Element {
    elements = Array(sequence)
  }

  public init(arrayLiteral elements: Element...) {
    self.init(elements)
  }

  public static var long: NameSpecification {
    [.long]
  }

  public static func customLong(_ name: String, withSingleDash: Bool = false)
    -> NameSpecification
  {
    [.customLong(name, withSingleDash: withSingleDash)]
  }

  public static var short: NameSpecification {
    [.short]
  }

  public static func customShort(
    _ char: Character, allowingJoined: Bool = false
  ) -> NameSpecification {
    [.customShort(char, allowingJoined: allowingJoined)]
  }

  public static var shortAndLong: NameSpecification {
    [.long, .short]
  }

  /// The concrete names for the property `key`, without repeats, in the
  /// order given.
  func makeNames(key: String) -> [Name] {
    var names: [Name] = []
    for element in elements {
      let name: Name
      switch element.base {
      case .long:
        name = .long(key.convertedToSnakeCase(separator: "-"))
      case .customLong(let text, let withSingleDash):
        name = withSingleDash ? .longWithSingleDash(text) : .long(text)
      case .short:
        guard let first = key.first else { continue }
        name = .short(first, allowingJoined: false)
      case .customShort(let char, let allowingJoined):
        name = .short(char, allowingJoined: allowingJoined)
      }
      if !names.contains(name) {
        names.append(name)
      }
    }
    return names
  }
}

/// One concrete name, as matched against a token.
enum Name: Hashable {
  case long(String)
  case short(Character, allowingJoined: Bool)
  case longWithSingleDash(String)

  static func == (lhs: Name, rhs: Name) -> Bool {
    switch (lhs, rhs) {
    case (.long(let a), .long(let b)),
      (.longWithSingleDash(let a), .longWithSingleDash(let b)):
      return a == b
    case (.short(let a, _), .short(let b, _)):
      return a == b
    default:
      return false
    }
  }

  func hash(into hasher: inout Hasher) {
    hasher.combine(synopsisString)
  }

  /// The name as typed: `--output`, `-o` or `-output`.
  var synopsisString: String {
    switch self {
    case .long(let name): return "--" + name
    case .short(let char, _): return "-" + String(char)
    case .longWithSingleDash(let name): return "-" + name
    }
  }

  /// The name without dashes, the default value name in help.
  var valueString: String {
    switch self {
    case .long(let name), .longWithSingleDash(let name): return name
    case .short(let char, _): return String(char)
    }
  }

  var isShort: Bool {
    if case .short = self { return true }
    return false
  }
}

extension Array where Element == Name {
  /// The name used in usage lines and value names: the first long one.
  var preferredName: Name? {
    first { !$0.isShort } ?? first
  }

  /// Short names first, as help lists them: `-o, --output, -output`.
  var partitioned: [Name] {
    filter(\.isShort) + filter { !$0.isShort }
  }
}
