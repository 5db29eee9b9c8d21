#if canImport(Glibc)
  import Glibc
#elseif canImport(Musl)
  import Musl
#elseif canImport(Darwin)
  import Darwin
#endif

/// A problem with the parsed values as a whole. Thrown from `validate()` or
/// `run()`, it is shown like a parse error: message, usage, exit status 64.
public struct ValidationError: Error, CustomStringConvertible {
  public internal(set) var message: String

  public init(_ message: String) {
    self.message = message
  }

  public var description: String {
    message
  }
}

/// Thrown to exit with a status and no message.
public struct ExitCode: Error, RawRepresentable, Hashable {
  public var rawValue: Int32

  public init(_ code: Int32) {
    rawValue = code
  }

  public init(rawValue: Int32) {
    self.init(rawValue)
  }

  public static let success = ExitCode(0)
  public static let failure = ExitCode(1)
  /// EX_USAGE from sysexits.h, the status for a bad command line.
  public static let validationFailure = ExitCode(64)

  public var isSuccess: Bool {
    rawValue == 0
  }
}

/// Thrown to stop with status 0 after printing help or a message.
public struct CleanExit: Error, CustomStringConvertible {
  enum Base {
    case helpRequest(ParsableCommand.Type?)
    case message(String)
  }

  var base: Base

  /// The help of the command whose `exit(withError:)` handles it.
  public static var helpRequest: CleanExit {
    CleanExit(base: .helpRequest(nil))
  }

  public static func helpRequest(_ type: ParsableCommand.Type) -> CleanExit {
    CleanExit(base: .helpRequest(type))
  }

  public static func helpRequest(_ command: ParsableCommand) -> CleanExit {
    helpRequest(type(of: command))
  }

  public static func message(_ text: String) -> CleanExit {
    CleanExit(base: .message(text))
  }

  public var description: String {
    switch base {
    case .helpRequest: return "--help"
    case .message(let text): return text
    }
  }
}

// MARK: - Internal errors

/// A problem found while reading tokens, with the argument's help line.
struct ParseFailure: Error {
  var message: String
  /// `--threads <threads>  Worker threads…`, shown as "Help:" under the error.
  var help: String

  init(_ message: String, help: String = "") {
    self.message = message
    self.help = help
  }
}

indirect enum ParserError: Error {
  case helpRequested
  case versionRequested
  case invalidInput(ParseFailure)
  case userValidationError(Error)
  case invalidState
  /// A failure on an empty command line, shown with the full help.
  case noArguments(ParserError)
}

/// A parser error and the commands it happened in, for the usage line.
struct CommandError: Error {
  var commandStack: [ParsableCommand.Type]
  var parserError: ParserError
}

// MARK: - Messages

/// What to print for an error and how to exit.
enum MessageInfo {
  case help(text: String)
  case validation(message: String, usage: String, help: String)
  case other(message: String, exitCode: ExitCode)

  init(error: Error, type: ParsableCommand.Type, columns: Int? = nil) {
    var commandStack: [ParsableCommand.Type] = [type]
    var parserError = ParserError.userValidationError(error)
    switch error {
    case let error as CommandError:
      commandStack = error.commandStack
      parserError = error.parserError
    case let error as ParserError:
      parserError = error
    case let error as ParseFailure:
      parserError = .invalidInput(error)
    default:
      break
    }

    var usage = HelpGenerator(commandStack: commandStack).usageMessage()
    if let helpName = commandStack.helpNames.preferredName {
      let names = commandStack.map { $0._commandName }.joined(separator: " ")
      usage +=
        "\n  See '\(names) \(helpName.synopsisString)' for more information."
    }
    if case .noArguments(let inner) = parserError {
      parserError = inner
      usage = "\n" + Self.helpText([type], columns: columns)
    }

    switch parserError {
    case .helpRequested:
      self = .help(text: Self.helpText(commandStack, columns: columns))
    case .versionRequested:
      let version = commandStack.map { $0.configuration.version }.last {
        !$0.isEmpty
      }
      self = .help(text: version ?? "Unspecified version")
    case .invalidInput(let failure):
      self = .validation(
        message: failure.message, usage: usage, help: failure.help)
    case .invalidState, .noArguments:
      self = .validation(
        message:
          "Internal error. Invalid state while parsing command-line arguments.",
        usage: usage, help: "")
    case .userValidationError(let error):
      self = Self.userError(
        error, type: type, commandStack: commandStack, usage: usage,
        columns: columns)
    }
  }

  /// Errors thrown by the command's own code, from `validate()` or `run()`.
  private static func userError(
    _ error: Error, type: ParsableCommand.Type,
    commandStack: [ParsableCommand.Type],
    usage: String, columns: Int?
  ) -> MessageInfo {
    switch error {
    case let error as ValidationError:
      return .validation(message: error.message, usage: usage, help: "")
    case let error as CleanExit:
      switch error.base {
      case .helpRequest(let requested?):
        let stack = CommandParser(root: type).commandStack(for: requested)
        return .help(text: helpText(stack, columns: columns))
      case .helpRequest(nil):
        return .help(text: helpText(commandStack, columns: columns))
      case .message(let text):
        return .help(text: text)
      }
    case let error as ExitCode:
      return .other(message: "", exitCode: error)
    default:
      return .other(message: String(describing: error), exitCode: .failure)
    }
  }

  private static func helpText(_ stack: [ParsableCommand.Type], columns: Int?)
    -> String
  {
    HelpGenerator(commandStack: stack).rendered(screenWidth: columns)
  }

  var message: String {
    switch self {
    case .help(let text): return text
    case .validation(let message, _, _): return message
    case .other(let message, _): return message
    }
  }

  /// `Error: …`, then `Help:  …` for a bad value, then the usage.
  var fullText: String {
    switch self {
    case .help(let text):
      return text
    case .validation(let message, let usage, let help):
      let errorLine = message.isEmpty ? "" : "Error: \(message)\n"
      let helpLine = help.isEmpty ? "" : "Help:  \(help)\n"
      return errorLine + helpLine + usage
    case .other(let message, _):
      return message.isEmpty ? "" : "Error: \(message)"
    }
  }

  var shouldExitCleanly: Bool {
    if case .help = self { return true }
    return false
  }

  var exitCode: ExitCode {
    switch self {
    case .help: return .success
    case .validation: return .validationFailure
    case .other(_, let code): return code
    }
  }
}

// MARK: - Process

/// Writes unbuffered to file descriptor 2; the C `stderr` global is shared
/// mutable state that Swift 6 won't let nonisolated code touch.
func writeToStandardError(_ text: String) {
  var text = text
  text.withUTF8 { bytes in
    guard let base = bytes.baseAddress else { return }
    var offset = 0
    while offset < bytes.count {
      let written = write(2, base + offset, bytes.count - offset)
      guard written > 0 else { return }
      offset += written
    }
  }
}

/// Flushes standard output and exits; the C library's `exit` under a name
/// that the `exit(withError:)` methods don't shadow.
func terminateProcess(_ code: ExitCode) -> Never {
  #if canImport(Glibc)
    Glibc.exit(code.rawValue)
  #elseif canImport(Musl)
    Musl.exit(code.rawValue)
  #elseif canImport(Darwin)
    Darwin.exit(code.rawValue)
  #endif
}
