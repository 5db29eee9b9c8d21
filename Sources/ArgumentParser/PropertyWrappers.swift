// The property wrappers keep their value in an `ArgumentStorage` object.
// `Mirror(reflecting: command)` hands the parser copies of the wrappers, and
// because a copy shares the object with the original, the parser's writes
// land in the command it returns (see `ArgumentDefinition.collect(from:)`).

/// A wrapper's value, shared by the wrapper and the copies `Mirror` makes.
///
/// `@unchecked Sendable` because the parser writes a storage only while it
/// builds the command, before any other code can reach it; afterwards a write
/// through `wrappedValue` swaps in a new storage rather than mutating this
/// one, so a storage that other code can see is never written again.
final class ArgumentStorage<Value>: @unchecked Sendable {
  /// Nil until parsed when the declaration has no default.
  var value: Value?
  /// Values read so far, kept apart so that an array's first parsed value
  /// replaces its default rather than appending to it.
  var pending: Value?

  init(_ value: Value?) {
    self.value = value
  }

  func read(wrapper: String) -> Value {
    guard let value else {
      fatalError(
        "\(wrapper) value read before parsing: use a command made by parse or "
          + "parseAsRoot, "
          + "or give the property a default value.")
    }
    return value
  }
}

/// Lets the parser find declarations among a command's `Mirror` children.
protocol ArgumentDeclaring {
  /// `key` is the property's name, which gives default names and value names.
  func definitions(key: String) -> [ArgumentDefinition]

  /// Runs `validate()` of an option group; nothing for other wrappers.
  func validateNested() throws
}

extension ArgumentDeclaring {
  func validateNested() throws {}
}

// MARK: - Parsing strategies

/// How the parser takes values after an option's name.
enum ValueParsing: Hashable, Sendable {
  case next, unconditional, scanningForValue, upToNextOption, remaining
}

/// How a single-value `@Option` finds its value.
public struct SingleValueParsingStrategy: Hashable, Sendable {
  var base: ValueParsing

  /// The next token, which must not look like an option (a negative number
  /// is a value unless it is a declared name).
  public static var next: SingleValueParsingStrategy {
    SingleValueParsingStrategy(base: .next)
  }

  /// The next token, whatever it looks like.
  public static var unconditional: SingleValueParsingStrategy {
    SingleValueParsingStrategy(base: .unconditional)
  }

  /// The first later token that is a value, skipping options in between.
  public static var scanningForValue: SingleValueParsingStrategy {
    SingleValueParsingStrategy(base: .scanningForValue)
  }
}

/// How an array `@Option` collects its values.
public struct ArrayParsingStrategy: Hashable, Sendable {
  var base: ValueParsing

  /// One value per use of the option: `--file a --file b`.
  public static var singleValue: ArrayParsingStrategy {
    ArrayParsingStrategy(base: .next)
  }

  /// One token per use, whatever it looks like.
  public static var unconditionalSingleValue: ArrayParsingStrategy {
    ArrayParsingStrategy(base: .unconditional)
  }

  /// Every following value up to the next option: `--size 640 480`.
  public static var upToNextOption: ArrayParsingStrategy {
    ArrayParsingStrategy(base: .upToNextOption)
  }

  /// Every following token, options included.
  public static var remaining: ArrayParsingStrategy {
    ArrayParsingStrategy(base: .remaining)
  }
}

/// How positional values fill an array `@Argument`.
enum PositionalParsing: Hashable, Sendable {
  case single, remaining, postTerminator, allUnrecognized
}

/// How an array `@Argument` collects values.
public struct ArgumentArrayParsingStrategy: Hashable, Sendable {
  var base: PositionalParsing

  /// The values left once options and earlier arguments have taken theirs.
  public static var remaining: ArgumentArrayParsingStrategy {
    ArgumentArrayParsingStrategy(base: .remaining)
  }

  /// Only the tokens after `--`.
  public static var postTerminator: ArgumentArrayParsingStrategy {
    ArgumentArrayParsingStrategy(base: .postTerminator)
  }

  /// Leftover values and unknown options alike, instead of errors.
  public static var allUnrecognized: ArgumentArrayParsingStrategy {
    ArgumentArrayParsingStrategy(base: .allUnrecognized)
  }
}

// MARK: - Values of @Option and @Argument

/// What `@Option` and `@Argument` know about their values, fixed when the
/// wrapper is made.
struct ValueDeclaration<Value>: Sendable {
  var help: ArgumentHelp?
  var isRepeating: Bool
  var isOptional: Bool
  var defaultValueDescription: String?
  var allValues: [String]
  var completion: CompletionKind?
  /// Adds one token to the values read so far; nil when it isn't valid.
  var accumulate: @Sendable (Value?, String) -> Value?
}

extension ValueDeclaration where Value: ExpressibleByArgument {
  static func single(
    initial: Value?, help: ArgumentHelp?, completion: CompletionKind?
  ) -> Self {
    ValueDeclaration(
      help: help, isRepeating: false, isOptional: initial != nil,
      defaultValueDescription: initial?.defaultValueDescription,
      allValues: Value.allValueStrings, completion: completion,
      accumulate: { _, token in Value(argument: token) })
  }
}

extension ValueDeclaration {
  static func optional<T: ExpressibleByArgument>(
    help: ArgumentHelp?, completion: CompletionKind?
  ) -> Self where Value == T? {
    ValueDeclaration(
      help: help, isRepeating: false, isOptional: true,
      defaultValueDescription: nil,
      allValues: T.allValueStrings, completion: completion,
      accumulate: { _, token in T(argument: token).map { .some($0) } })
  }

  static func array<T: ExpressibleByArgument>(
    initial: [T]?, help: ArgumentHelp?, completion: CompletionKind?
  ) -> Self where Value == [T] {
    ValueDeclaration(
      help: help, isRepeating: true, isOptional: initial != nil,
      defaultValueDescription: initial?.map(\.defaultValueDescription).joined(
        separator: ", "),
      allValues: T.allValueStrings, completion: completion,
      accumulate: { values, token in
        T(argument: token).map { (values ?? []) + [$0] }
      })
  }

  func definition(
    kind: ArgumentDefinition.Kind, names: [Name], key: String,
    storage: ArgumentStorage<Value>
  ) -> ArgumentDefinition {
    let accumulate = self.accumulate
    return ArgumentDefinition(
      kind: kind, names: names, key: key, help: help ?? ArgumentHelp(),
      isRepeating: isRepeating, isOptional: isOptional,
      defaultValueDescription: defaultValueDescription, allValues: allValues,
      sink: ArgumentSink(
        take: { token in
          guard let value = accumulate(storage.pending, token) else {
            return false
          }
          storage.pending = value
          return true
        },
        commit: {
          if let pending = storage.pending {
            storage.value = pending
            storage.pending = nil
          }
        },
        hasValue: { storage.value != nil }))
  }
}

// MARK: - @Option

/// A named value: `--threads 4`, `--threads=4`, `-o file`, `-size 640 480`.
@propertyWrapper
public struct Option<Value>: CustomStringConvertible {
  var storage: ArgumentStorage<Value>
  let names: NameSpecification
  let parsing: ValueParsing
  let declaration: ValueDeclaration<Value>

  init(
    initial: Value?, names: NameSpecification, parsing: ValueParsing,
    declaration: ValueDeclaration<Value>
  ) {
    storage = ArgumentStorage(initial)
    self.names = names
    self.parsing = parsing
    self.declaration = declaration
  }

  /// Never called: its presence makes the compiler accept a bare `@Option`
  /// without parentheses and pick the matching initialiser from the
  /// extensions, as in the real package.
  @available(
    *, unavailable,
    message:
      """
        A default value must be provided unless the value type conforms to \
        ExpressibleByArgument.
        """
  )
  public init() {
    fatalError("unavailable")
  }

  public var wrappedValue: Value {
    get { storage.read(wrapper: "@Option") }
    set { storage = ArgumentStorage(newValue) }
  }

  public var description: String {
    storage.value.map { String(describing: $0) } ?? "Option(no value)"
  }
}

extension Option: Sendable where Value: Sendable {}

extension Option: ArgumentDeclaring {
  func definitions(key: String) -> [ArgumentDefinition] {
    [
      declaration.definition(
        kind: .option(parsing), names: names.makeNames(key: key), key: key,
        storage: storage)
    ]
  }
}

extension Option where Value: ExpressibleByArgument {
  /// An option with a default, from the property's initialiser.
  public init(
    wrappedValue: Value,
    name: NameSpecification = .long,
    parsing: SingleValueParsingStrategy = .next,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) {
    self.init(
      initial: wrappedValue, names: name, parsing: parsing.base,
      declaration: .single(
        initial: wrappedValue, help: help, completion: completion))
  }

  /// A required option.
  public init(
    name: NameSpecification = .long,
    parsing: SingleValueParsingStrategy = .next,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) {
    self.init(
      initial: nil, names: name, parsing: parsing.base,
      declaration: .single(initial: nil, help: help, completion: completion))
  }
}

extension Option {
  /// An optional option written `var x: T? = nil`.
  public init<T: ExpressibleByArgument>(
    wrappedValue: _OptionalNilComparisonType,
    name: NameSpecification = .long,
    parsing: SingleValueParsingStrategy = .next,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == T? {
    self.init(name: name, parsing: parsing, help: help, completion: completion)
  }

  /// An optional option, nil when not given.
  public init<T: ExpressibleByArgument>(
    name: NameSpecification = .long,
    parsing: SingleValueParsingStrategy = .next,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == T? {
    self.init(
      initial: .some(nil), names: name, parsing: parsing.base,
      declaration: .optional(help: help, completion: completion))
  }

  /// An array option with a default; values given replace the default.
  public init<T: ExpressibleByArgument>(
    wrappedValue: [T],
    name: NameSpecification = .long,
    parsing: ArrayParsingStrategy = .singleValue,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == [T] {
    self.init(
      initial: wrappedValue, names: name, parsing: parsing.base,
      declaration: .array(
        initial: wrappedValue, help: help, completion: completion))
  }

  /// An array option that must be given at least once.
  public init<T: ExpressibleByArgument>(
    name: NameSpecification = .long,
    parsing: ArrayParsingStrategy = .singleValue,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == [T] {
    self.init(
      initial: nil, names: name, parsing: parsing.base,
      declaration: .array(initial: nil, help: help, completion: completion))
  }
}

// MARK: - @Argument

/// A positional value, filled in declaration order from the tokens that are
/// neither options nor option values.
@propertyWrapper
public struct Argument<Value>: CustomStringConvertible {
  var storage: ArgumentStorage<Value>
  let parsing: PositionalParsing
  let declaration: ValueDeclaration<Value>

  init(
    initial: Value?, parsing: PositionalParsing,
    declaration: ValueDeclaration<Value>
  ) {
    storage = ArgumentStorage(initial)
    self.parsing = parsing
    self.declaration = declaration
  }

  /// Never called: its presence makes the compiler accept a bare `@Argument`
  /// without parentheses and pick the matching initialiser from the
  /// extensions, as in the real package.
  @available(
    *, unavailable,
    message:
      """
        A default value must be provided unless the value type conforms to \
        ExpressibleByArgument.
        """
  )
  public init() {
    fatalError("unavailable")
  }

  public var wrappedValue: Value {
    get { storage.read(wrapper: "@Argument") }
    set { storage = ArgumentStorage(newValue) }
  }

  public var description: String {
    storage.value.map { String(describing: $0) } ?? "Argument(no value)"
  }
}

extension Argument: Sendable where Value: Sendable {}

extension Argument: ArgumentDeclaring {
  func definitions(key: String) -> [ArgumentDefinition] {
    [
      declaration.definition(
        kind: .positional(parsing), names: [], key: key, storage: storage)
    ]
  }
}

extension Argument where Value: ExpressibleByArgument {
  /// An argument with a default, from the property's initialiser.
  public init(
    wrappedValue: Value, help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) {
    self.init(
      initial: wrappedValue, parsing: .single,
      declaration: .single(
        initial: wrappedValue, help: help, completion: completion))
  }

  /// A required argument.
  public init(help: ArgumentHelp? = nil, completion: CompletionKind? = nil) {
    self.init(
      initial: nil, parsing: .single,
      declaration: .single(initial: nil, help: help, completion: completion))
  }
}

extension Argument {
  /// An optional argument written `var x: T? = nil`.
  public init<T: ExpressibleByArgument>(
    wrappedValue: _OptionalNilComparisonType,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == T? {
    self.init(help: help, completion: completion)
  }

  /// An optional argument, nil when not given.
  public init<T: ExpressibleByArgument>(
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == T? {
    self.init(
      initial: .some(nil), parsing: .single,
      declaration: .optional(help: help, completion: completion))
  }

  /// An array argument with a default; values given replace the default.
  public init<T: ExpressibleByArgument>(
    wrappedValue: [T],
    parsing: ArgumentArrayParsingStrategy = .remaining,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == [T] {
    self.init(
      initial: wrappedValue, parsing: parsing.base,
      declaration: .array(
        initial: wrappedValue, help: help, completion: completion))
  }

  /// An array argument that needs at least one value.
  public init<T: ExpressibleByArgument>(
    parsing: ArgumentArrayParsingStrategy = .remaining,
    help: ArgumentHelp? = nil,
    completion: CompletionKind? = nil
  ) where Value == [T] {
    self.init(
      initial: nil, parsing: parsing.base,
      declaration: .array(initial: nil, help: help, completion: completion))
  }
}

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

// MARK: - @OptionGroup

/// Another `ParsableArguments` type's arguments, parsed as if declared here;
/// lets commands share options.
@propertyWrapper
public struct OptionGroup<Value: ParsableArguments>: CustomStringConvertible {
  var storage: ArgumentStorage<Value>
  let title: String
  let visibility: ArgumentVisibility

  /// A non-empty `title` lists the group's arguments under their own heading.
  public init(title: String = "", visibility: ArgumentVisibility = .default) {
    storage = ArgumentStorage(Value())
    self.title = title
    self.visibility = visibility
  }

  public var wrappedValue: Value {
    get { storage.read(wrapper: "@OptionGroup") }
    set { storage = ArgumentStorage(newValue) }
  }

  public var description: String {
    storage.value.map { String(describing: $0) } ?? "OptionGroup(no value)"
  }
}

extension OptionGroup: Sendable where Value: Sendable {}

extension OptionGroup: ArgumentDeclaring {
  func definitions(key: String) -> [ArgumentDefinition] {
    guard let value = storage.value else { return [] }
    return ArgumentDefinition.collect(from: value).map { definition in
      var definition = definition
      if definition.groupTitle.isEmpty {
        definition.groupTitle = title
      }
      if visibility.level.rawValue > definition.help.visibility.level.rawValue {
        definition.help.visibility = visibility
      }
      return definition
    }
  }

  func validateNested() throws {
    guard var value = storage.value else { return }
    try ArgumentDefinition.validateGroups(in: value)
    try value.validate()
    storage.value = value
  }
}
