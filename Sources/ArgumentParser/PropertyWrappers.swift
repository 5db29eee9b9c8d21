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
