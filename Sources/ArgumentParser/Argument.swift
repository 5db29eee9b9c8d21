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
