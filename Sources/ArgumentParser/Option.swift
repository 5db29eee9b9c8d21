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
