// MARK: - @Flag

/// Which extra name turns a Boolean flag off.
public struct FlagInversion: Hashable, Sendable {
  enum Base: Hashable, Sendable {
    case prefixedNo, prefixedEnableDisable
  }

  var base: Base

  /// `--flag` and `--no-flag`.
  public static var prefixedNo: FlagInversion {
    FlagInversion(base: .prefixedNo)
  }

  /// `--enable-flag` and `--disable-flag`.
  public static var prefixedEnableDisable: FlagInversion {
    FlagInversion(base: .prefixedEnableDisable)
  }
}

/// What happens when a flag and its inversion are both given.
public struct FlagExclusivity: Hashable, Sendable {
  enum Base: Hashable, Sendable {
    case exclusive, chooseFirst, chooseLast
  }

  var base: Base

  /// Giving more than one is an error.
  public static var exclusive: FlagExclusivity {
    FlagExclusivity(base: .exclusive)
  }

  public static var chooseFirst: FlagExclusivity {
    FlagExclusivity(base: .chooseFirst)
  }

  public static var chooseLast: FlagExclusivity {
    FlagExclusivity(base: .chooseLast)
  }
}

/// A named switch without a value: `--stats`, or a count of `-v -v -v`.
@propertyWrapper
public struct Flag<Value>: CustomStringConvertible {
  var storage: ArgumentStorage<Value>
  let names: NameSpecification
  let help: ArgumentHelp?
  let inversion: FlagInversion?
  /// Nil for a counting flag, where every use counts.
  let exclusivity: FlagExclusivity?
  /// Folds the uses kept after exclusivity (`true` for a name, `false` for
  /// an inverted name), never empty, into the value.
  let resolve: @Sendable ([Bool]) -> Value
  let initialIsOn: Bool?

  /// Never called: its presence makes the compiler accept a bare `@Flag`
  /// without parentheses and pick the matching initialiser from the
  /// extensions, as in the real package.
  @available(*, unavailable, message: "A flag's value must be Bool or Int.")
  public init() {
    fatalError("unavailable")
  }

  public var wrappedValue: Value {
    get { storage.read(wrapper: "@Flag") }
    set { storage = ArgumentStorage(newValue) }
  }

  public var description: String {
    storage.value.map { String(describing: $0) } ?? "Flag(no value)"
  }
}

extension Flag: Sendable where Value: Sendable {}

extension Flag: ArgumentDeclaring {
  func definitions(key: String) -> [ArgumentDefinition] {
    let baseNames = names.makeNames(key: key)
    var positive = baseNames
    var negative: [Name] = []
    if let inversion {
      let shorts = baseNames.filter(\.isShort)
      let longs = baseNames.filter { !$0.isShort }
      switch inversion.base {
      case .prefixedNo:
        negative = longs.map { $0.prefixed("no-") }
      case .prefixedEnableDisable:
        positive = shorts + longs.map { $0.prefixed("enable-") }
        negative = longs.map { $0.prefixed("disable-") }
      }
    }
    var defaultDescription: String?
    if inversion != nil, let initialIsOn {
      defaultDescription =
        (initialIsOn ? positive : negative).preferredName?.synopsisString
    }
    let storage = self.storage
    let resolve = self.resolve
    return [
      ArgumentDefinition(
        kind: .flag(exclusivity), names: positive, invertedNames: negative,
        key: key,
        help: help ?? ArgumentHelp(), isRepeating: false,
        isOptional: storage.value != nil,
        defaultValueDescription: defaultDescription, allValues: [],
        sink: ArgumentSink(
          flag: { uses in storage.value = resolve(uses) },
          commit: {},
          hasValue: { storage.value != nil }))
    ]
  }
}

extension Flag where Value == Bool {
  /// A flag that is off unless given; help shows no default for it.
  public init(
    wrappedValue: Bool, name: NameSpecification = .long,
    help: ArgumentHelp? = nil
  ) {
    storage = ArgumentStorage(wrappedValue)
    names = name
    self.help = help
    inversion = nil
    exclusivity = .chooseLast
    resolve = { _ in true }
    initialIsOn = wrappedValue
  }

  /// A flag that is off unless given.
  public init(name: NameSpecification = .long, help: ArgumentHelp? = nil) {
    self.init(wrappedValue: false, name: name, help: help)
  }

  /// A flag with a second name that turns it off: `--flag` / `--no-flag`.
  public init(
    wrappedValue: Bool,
    name: NameSpecification = .long,
    inversion: FlagInversion,
    exclusivity: FlagExclusivity = .chooseLast,
    help: ArgumentHelp? = nil
  ) {
    self.init(
      initial: wrappedValue, name: name, inversion: inversion,
      exclusivity: exclusivity, help: help)
  }

  /// A flag whose name or inversion must be given.
  public init(
    name: NameSpecification = .long,
    inversion: FlagInversion,
    exclusivity: FlagExclusivity = .chooseLast,
    help: ArgumentHelp? = nil
  ) {
    self.init(
      initial: nil, name: name, inversion: inversion, exclusivity: exclusivity,
      help: help)
  }

  private init(
    initial: Bool?, name: NameSpecification, inversion: FlagInversion,
    exclusivity: FlagExclusivity, help: ArgumentHelp?
  ) {
    storage = ArgumentStorage(initial)
    names = name
    self.help = help
    self.inversion = inversion
    self.exclusivity = exclusivity
    resolve = { uses in uses.last ?? false }
    initialIsOn = initial
  }
}

extension Flag where Value == Int {
  /// Counts the uses: `-v -v -v` or `-vvv` gives 3.
  public init(name: NameSpecification = .long, help: ArgumentHelp? = nil) {
    storage = ArgumentStorage(0)
    names = name
    self.help = help
    inversion = nil
    exclusivity = nil
    resolve = { uses in uses.count }
    initialIsOn = nil
  }
}

extension Name {
  fileprivate func prefixed(_ prefix: String) -> Name {
    switch self {
    case .long(let name): return .long(prefix + name)
    case .longWithSingleDash(let name):
      return .longWithSingleDash(prefix + name)
    case .short: return self
    }
  }
}
