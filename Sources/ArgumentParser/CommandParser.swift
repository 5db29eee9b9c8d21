// The descent through subcommands to the command the arguments name.

// MARK: - Subcommands

/// Found a help flag: `parseAsRoot` answers with a `HelpCommand`.
struct HelpRequested: Error {}

/// Descends from the root command through the subcommands that the tokens
/// name, parsing each command's own options on the way.
struct CommandParser {
  let root: ParsableCommand.Type

  func parse(_ arguments: [String]) throws -> ParsableCommand {
    var stack: [ParsableCommand.Type] = [root]
    do {
      return try descend(arguments, stack: &stack, isEmpty: arguments.isEmpty)
    } catch is HelpRequested {
      return HelpCommand(commandStack: stack)
    }
  }

  private func descend(
    _ arguments: [String], stack: inout [ParsableCommand.Type], isEmpty: Bool
  ) throws -> ParsableCommand {
    var tokens = arguments
    while let type = stack.last {
      let configuration = type.configuration
      var command = type.init()
      let reader = ArgumentReader(ArgumentDefinition.collect(from: command))
      if !configuration.subcommands.isEmpty {
        let ownCount = reader.leadingOptionCount(tokens)
        let own = Array(tokens[..<ownCount])
        let rest = Array(tokens[ownCount...])
        if let next = rest.first {
          if let subcommand = configuration.subcommands.first(where: {
            $0._commandName == next || $0.configuration.aliases.contains(next)
          }) {
            _ = try finish(
              &command, reader: reader, tokens: own, remaining: tokens,
              stack: stack, isEmpty: isEmpty)
            stack.append(subcommand)
            tokens = Array(rest.dropFirst())
            continue
          }
          if stack.count == 1, next == "help" {
            return HelpCommand(
              commandStack: commandStack(forNames: Array(rest.dropFirst())))
          }
        }
        if let subcommand = configuration.defaultSubcommand {
          _ = try finish(
            &command, reader: reader, tokens: own, remaining: tokens,
            stack: stack, isEmpty: isEmpty)
          // Before the default subcommand takes over, a help or version
          // flag counts only as the one argument left, as in the real
          // package: `raytrace --help` is the root's help, `raytrace SCENE
          // --help` the default subcommand's.
          if rest.count == 1 {
            try checkForBuiltInFlags(rest, stack: stack)
          }
          stack.append(subcommand)
          tokens = rest
          continue
        }
      }
      let leftover = try finish(
        &command, reader: reader, tokens: tokens, remaining: tokens,
        stack: stack, isEmpty: isEmpty)
      try checkForBuiltInFlags(tokens, stack: stack)
      if let leftover {
        throw parseError(leftover, stack: stack, isEmpty: isEmpty)
      }
      return command
    }
    throw CommandError(commandStack: [root], parserError: .invalidState)
  }

  /// Reads a command's tokens and validates it, tagging errors with the
  /// command stack so that the message shows the right usage. In the real
  /// package's order: a missing or invalid value first, then (unless a help
  /// flag is among the `remaining` tokens) a missing argument and the
  /// command's `validate()`; an unknown option or unexpected argument is
  /// returned, for the caller to report after the help flags.
  private func finish(
    _ command: inout ParsableCommand, reader: ArgumentReader, tokens: [String],
    remaining: [String], stack: [ParsableCommand.Type], isEmpty: Bool
  ) throws -> ParseFailure? {
    let outcome: ArgumentReader.Outcome
    do {
      outcome = try reader.read(tokens)
    } catch let failure as ParseFailure {
      throw parseError(failure, stack: stack, isEmpty: isEmpty)
    }
    if let missing = outcome.missing {
      try checkForBuiltInFlags(remaining, stack: stack)
      throw parseError(missing, stack: stack, isEmpty: isEmpty)
    }
    do {
      try ArgumentDefinition.validateGroups(in: command)
      try command.validate()
    } catch {
      try checkForBuiltInFlags(remaining, stack: stack)
      throw CommandError(
        commandStack: stack, parserError: .userValidationError(error))
    }
    return outcome.leftover
  }

  private func parseError(
    _ failure: ParseFailure, stack: [ParsableCommand.Type], isEmpty: Bool
  ) -> CommandError {
    let error = ParserError.invalidInput(failure)
    return CommandError(
      commandStack: stack, parserError: isEmpty ? .noArguments(error) : error)
  }

  /// Help and version flags win over what remains to report.
  private func checkForBuiltInFlags(
    _ tokens: [String], stack: [ParsableCommand.Type]
  ) throws {
    let options = tokens.prefix { $0 != "--" }
    let helpNames = Set(stack.helpNames.map(\.synopsisString))
    if options.contains(where: helpNames.contains) {
      throw HelpRequested()
    }
    if stack.contains(where: { !$0.configuration.version.isEmpty }),
      options.contains("--version")
    {
      throw CommandError(commandStack: stack, parserError: .versionRequested)
    }
  }

  /// The commands that `names` lead to from the root, stopping at the first
  /// name that is not a subcommand.
  func commandStack(forNames names: [String]) -> [ParsableCommand.Type] {
    var stack: [ParsableCommand.Type] = [root]
    for name in names {
      guard let current = stack.last,
        let next = current.configuration.subcommands.first(where: {
          $0._commandName == name || $0.configuration.aliases.contains(name)
        })
      else { break }
      stack.append(next)
    }
    return stack
  }

  /// The path from the root to `type`; just the root when `type` isn't
  /// below it.
  func commandStack(for type: ParsableCommand.Type) -> [ParsableCommand.Type] {
    func path(from node: ParsableCommand.Type, depth: Int)
      -> [ParsableCommand.Type]?
    {
      if node == type { return [node] }
      // Guards against a command listing itself among its subcommands.
      guard depth < 32 else { return nil }
      for child in node.configuration.subcommands {
        if let rest = path(from: child, depth: depth + 1) {
          return [node] + rest
        }
      }
      return nil
    }
    return path(from: root, depth: 0) ?? [root]
  }
}

extension Array where Element == ParsableCommand.Type {
  /// The help names of the innermost command that sets them; `-h, --help`
  /// otherwise.
  var helpNames: [Name] {
    let specification =
      last(where: { $0.configuration.helpNames != nil })?.configuration
      .helpNames
      ?? [.short, .long]
    return specification.makeNames(key: "help")
  }
}

/// What `parseAsRoot` returns for `--help` or `help <subcommand>`: running it
/// prints the help of the commands in `commandStack`.
struct HelpCommand: ParsableCommand {
  static var configuration: CommandConfiguration {
    CommandConfiguration(
      commandName: "help", abstract: "Show subcommand help information.")
  }

  var commandStack: [ParsableCommand.Type] = []

  init() {}

  init(commandStack: [ParsableCommand.Type]) {
    self.commandStack = commandStack
  }

  func run() throws {
    throw CommandError(commandStack: commandStack, parserError: .helpRequested)
  }
}
