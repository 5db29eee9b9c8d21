// A stand-in for swift-argument-parser (apple/swift-argument-parser), holding
// only the parts raytrace uses, under the same names and with the same help
// layout, error messages and exit codes. Deleting this folder and depending on
// the real package's "ArgumentParser" product instead needs no change to the
// code that imports it.
//
// The one deliberate difference in mechanism: the real package decodes parsed
// values through `Decodable`; here each property wrapper keeps its value in a
// shared box, and the parser finds the wrappers of a fresh `Self()` through
// `Mirror` and fills their boxes (see PropertyWrappers.swift).

#if compiler(>=6.2)
  /// Lets metatypes of commands sit in `Sendable` values such as
  /// `CommandConfiguration.subcommands`, as in the real package.
  public typealias _SendableMetatype = SendableMetatype
#else
  public typealias _SendableMetatype = Any
#endif

/// A type whose properties are filled from command-line arguments.
public protocol ParsableArguments: _SendableMetatype {
  /// The parser makes each instance with this initialiser, so every property
  /// wrapper must get its declaration from a property initialiser or default.
  init()

  /// Checks the parsed values together; a thrown `ValidationError` is shown
  /// with the usage, like a parse error.
  mutating func validate() throws
}

extension ParsableArguments {
  public mutating func validate() throws {}
}

/// A command-line program or one of its subcommands.
public protocol ParsableCommand: ParsableArguments {
  static var configuration: CommandConfiguration { get }

  /// The name used on the command line and in help: `configuration.commandName`
  /// or the type's name in kebab case.
  static var _commandName: String { get }

  /// The command's work, called by `main()` after parsing and validation.
  mutating func run() throws
}

extension ParsableCommand {
  public static var configuration: CommandConfiguration {
    CommandConfiguration()
  }

  public static var _commandName: String {
    configuration.commandName
      ?? String(describing: Self.self).convertedToSnakeCase(separator: "-")
  }

  /// A command that only groups subcommands has nothing to do but show help.
  public mutating func run() throws {
    throw CleanExit.helpRequest(self)
  }
}

/// How a command presents itself and which subcommands it dispatches to.
public struct CommandConfiguration: Sendable {
  public var commandName: String?
  public var abstract: String
  /// Replaces the generated usage line when set.
  public var usage: String?
  public var discussion: String
  /// When non-empty, adds a `--version` flag that prints it.
  public var version: String
  /// Whether the parent's help lists this command.
  public var shouldDisplay: Bool
  public var subcommands: [ParsableCommand.Type]
  /// Parses the arguments when none of them names a subcommand.
  public var defaultSubcommand: ParsableCommand.Type?
  /// Replaces `-h, --help` when set; an empty list removes the help flag.
  public var helpNames: NameSpecification?
  /// More names that select this command as a subcommand.
  public var aliases: [String]

  public init(
    commandName: String? = nil,
    abstract: String = "",
    usage: String? = nil,
    discussion: String = "",
    version: String = "",
    shouldDisplay: Bool = true,
    subcommands: [ParsableCommand.Type] = [],
    defaultSubcommand: ParsableCommand.Type? = nil,
    helpNames: NameSpecification? = nil,
    aliases: [String] = []
  ) {
    self.commandName = commandName
    self.abstract = abstract
    self.usage = usage
    self.discussion = discussion
    self.version = version
    self.shouldDisplay = shouldDisplay
    self.subcommands = subcommands
    self.defaultSubcommand = defaultSubcommand
    self.helpNames = helpNames
    self.aliases = aliases
  }
}

// MARK: - Entry points

extension ParsableArguments {
  /// A plain `ParsableArguments` type is parsed as a command without
  /// subcommands, as the real package does.
  static var asCommand: ParsableCommand.Type {
    (self as? ParsableCommand.Type) ?? ArgumentsCommand<Self>.self
  }

  /// Parses `arguments` (the process's arguments when nil) into a validated
  /// instance, or throws an error to hand to `exit(withError:)`.
  public static func parse(_ arguments: [String]? = nil) throws -> Self {
    switch try asCommand.parseAsRoot(arguments) {
    case is HelpCommand:
      throw ParserError.helpRequested
    case let wrapper as ArgumentsCommand<Self>:
      return wrapper.arguments
    case let result as Self:
      return result
    default:
      // A subcommand was named; only `parseAsRoot` can return it.
      throw ParserError.invalidState
    }
  }

  /// Like `parse(_:)`, but prints the error or help and exits instead of
  /// throwing.
  public static func parseOrExit(_ arguments: [String]? = nil) -> Self {
    do {
      return try parse(arguments)
    } catch {
      exit(withError: error)
    }
  }

  /// The error's message alone, without "Error:" or usage; help text for a
  /// help request.
  public static func message(for error: Error) -> String {
    MessageInfo(error: error, type: asCommand).message
  }

  /// What `exit(withError:)` prints for `error`.
  public static func fullMessage(for error: Error, columns: Int? = nil)
    -> String
  {
    MessageInfo(error: error, type: asCommand, columns: columns).fullText
  }

  /// The help screen, wrapped to `columns` (80 when nil).
  public static func helpMessage(
    includeHidden: Bool = false, columns: Int? = nil
  ) -> String {
    HelpGenerator(commandStack: [asCommand], includeHidden: includeHidden)
      .rendered(screenWidth: columns)
  }

  /// The status `exit(withError:)` exits with for `error`.
  public static func exitCode(for error: Error) -> ExitCode {
    MessageInfo(error: error, type: asCommand).exitCode
  }

  /// Prints the message for `error` (help to standard output, anything else
  /// to standard error) and exits with its code; exits with 0 when nil.
  public static func exit(withError error: Error? = nil) -> Never {
    guard let error else { terminateProcess(.success) }
    let info = MessageInfo(error: error, type: asCommand)
    let text = info.fullText
    if !text.isEmpty {
      if info.shouldExitCleanly {
        print(text)
      } else {
        writeToStandardError(text + "\n")
      }
    }
    terminateProcess(info.exitCode)
  }
}

extension ParsableCommand {
  /// Parses `arguments` (the process's arguments when nil), descending into
  /// subcommands, and returns the validated command to run.
  public static func parseAsRoot(_ arguments: [String]? = nil) throws
    -> ParsableCommand
  {
    try CommandParser(root: self).parse(
      arguments ?? Array(CommandLine.arguments.dropFirst()))
  }

  /// The help screen of `subcommand`, as reached from this root command.
  public static func helpMessage(
    for subcommand: ParsableCommand.Type, includeHidden: Bool = false,
    columns: Int? = nil
  ) -> String {
    HelpGenerator(
      commandStack: CommandParser(root: self).commandStack(for: subcommand),
      includeHidden: includeHidden
    ).rendered(screenWidth: columns)
  }

  /// Parses `arguments`, runs the chosen command and exits on error.
  public static func main(_ arguments: [String]?) {
    do {
      var command = try parseAsRoot(arguments)
      try command.run()
    } catch {
      exit(withError: error)
    }
  }

  /// The entry point that `@main` calls.
  public static func main() {
    main(nil)
  }
}

/// Lets a plain `ParsableArguments` type go through the command parser.
struct ArgumentsCommand<Arguments: ParsableArguments>: ParsableCommand {
  static var configuration: CommandConfiguration {
    CommandConfiguration(
      commandName: String(describing: Arguments.self).convertedToSnakeCase(
        separator: "-"))
  }

  @OptionGroup var arguments: Arguments
}
