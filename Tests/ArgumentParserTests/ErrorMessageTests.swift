import ArgumentParser
import XCTest

final class ErrorMessageTests: XCTestCase {
  static let paintUsage = """
    Usage: paint <scene> [--output <file>] [--size <w h> ...] [--finish <finish>] [--png-level <png-level>] [--stats]
      See 'paint --help' for more information.
    """

  /// The error that parsing `arguments` throws, or a failure.
  func parseError<C: ParsableCommand>(
    _ type: C.Type, _ arguments: [String], file: StaticString = #filePath,
    line: UInt = #line
  ) -> Error? {
    do {
      var command = try C.parseAsRoot(arguments)
      try command.run()
      XCTFail("Expected an error for \(arguments)", file: file, line: line)
      return nil
    } catch {
      return error
    }
  }

  func assertMessage<C: ParsableCommand>(
    _ type: C.Type, _ arguments: [String], _ message: String,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    guard let error = parseError(type, arguments, file: file, line: line) else {
      return
    }
    XCTAssertEqual(C.message(for: error), message, file: file, line: line)
    XCTAssertEqual(
      C.exitCode(for: error), .validationFailure, file: file, line: line)
  }

  func testError_UnknownOption() {
    assertMessage(
      Paint.self, ["s", "--frobnicate"], "Unknown option '--frobnicate'")
    assertMessage(Paint.self, ["s", "-x"], "Unknown option '-x'")
  }

  /// The real package validates a command before it reports what is left
  /// over: `validate()`'s error wins over an unknown option or an unexpected
  /// argument (raytrace parses twice to report those first).
  func testError_ValidationBeforeUnknownOptionAndUnexpectedArgument() {
    let both = "Give the scene either as an argument or with -input, not both."
    assertMessage(RenderLike.self, ["s", "-input", "t", "--frob"], both)
    assertMessage(RenderLike.self, ["s", "-input", "t", "-o", "a", "b"], both)
  }

  /// A missing or invalid value is reported before a help flag, as in the
  /// real package; a validation error or unknown option is not.
  func testError_MissingOrInvalidValueBeforeHelp() {
    assertMessage(
      RenderLike.self, ["s", "--shift", "--help"],
      "Missing value for '--shift <shift>'")
    assertMessage(
      RenderLike.self, ["s", "--shift", "x", "--help"],
      "The value 'x' is invalid for '--shift <shift>'")
    for arguments in [
      ["s", "-input", "t", "--help"], ["s", "--frob", "--help"],
    ] {
      XCTAssertThrowsError(try RenderLike.parse(arguments)) {
        XCTAssertEqual(RenderLike.exitCode(for: $0), .success, "\(arguments)")
      }
    }
  }

  func testError_UnknownOptionSuggestsClosestName() {
    assertMessage(
      Paint.self, ["s", "--outptu", "a.png"],
      "Unknown option '--outptu'. Did you mean '--output'?")
    assertMessage(
      Paint.self, ["s", "-outptu", "a.png"],
      "Unknown option '-outptu'. Did you mean '-output'?")
    assertMessage(
      Paint.self, ["s", "--png-levl", "3"],
      "Unknown option '--png-levl'. Did you mean '--png-level'?")
  }

  func testError_MissingValue() {
    assertMessage(
      Paint.self, ["s", "--size"], "Missing value for '--size <w h>'")
    assertMessage(
      Paint.self, ["s", "-o", "--stats"], "Missing value for '-o <file>'")
  }

  func testError_MissingValueFullMessage() {
    guard let error = parseError(Paint.self, ["s", "-size"]) else { return }
    XCTAssertEqual(
      Paint.fullMessage(for: error),
      """
      Error: Missing value for '-size <w h>'
      Help:  -size <w h>  Width and height.

      """ + Self.paintUsage)
  }

  func testError_InvalidValue() {
    assertMessage(
      Paint.self, ["s", "--png-level", "abc"],
      "The value 'abc' is invalid for '--png-level <png-level>'")
    assertMessage(
      Paint.self, ["s", "--size", "4", "x"],
      "The value 'x' is invalid for '--size <w h>'")
  }

  func testError_InvalidEnumValueListsChoices() {
    assertMessage(
      Paint.self, ["s", "--finish", "shiny"],
      "The value 'shiny' is invalid for '--finish <finish>'. Please provide one of 'matte' and 'gloss'."
    )
  }

  func testError_InvalidPositionalValue() {
    struct Count: ParsableCommand {
      @Argument var count: Int
    }
    assertMessage(
      Count.self, ["many"], "The value 'many' is invalid for '<count>'")
  }

  func testError_UnexpectedArguments() {
    assertMessage(Paint.self, ["s", "t"], "Unexpected argument 't'")
    assertMessage(
      Paint.self, ["s", "t", "u"], "2 unexpected arguments: 't', 'u'")
  }

  func testError_FlagWithValue() {
    assertMessage(
      Paint.self, ["s", "--stats=yes"],
      "The option '--stats' does not take any value, but 'yes' was specified.")
  }

  func testError_MissingArgumentOnEmptyLineShowsHelp() {
    guard let error = parseError(Paint.self, []) else { return }
    XCTAssertEqual(
      Paint.message(for: error), "Missing expected argument '<scene>'")
    XCTAssertEqual(Paint.exitCode(for: error), .validationFailure)
    XCTAssertEqual(
      Paint.fullMessage(for: error),
      "Error: Missing expected argument '<scene>'\nHelp:  <scene>  The scene file.\n\n"
        + Paint.helpMessage())
  }

  func testError_MissingRequiredOption() {
    struct Named: ParsableCommand {
      @Option(help: "Your name.") var name: String
      @Flag var loud = false
    }
    assertMessage(
      Named.self, ["--loud"], "Missing expected argument '--name <name>'")
  }

  func testError_ValidationErrorFromValidate() {
    guard let error = parseError(Paint.self, ["s", "--size", "1", "2", "3"])
    else { return }
    XCTAssertEqual(Paint.exitCode(for: error), .validationFailure)
    XCTAssertEqual(
      Paint.fullMessage(for: error),
      "Error: --size takes two values, W and H; got 3.\n" + Self.paintUsage)
  }

  func testError_ValidationErrorFromRunShowsRootUsage() {
    guard let error = parseError(Draw.self, ["report"]) else { return }
    XCTAssertEqual(Draw.exitCode(for: error), .validationFailure)
    XCTAssertEqual(
      Draw.fullMessage(for: error),
      """
      Error: Report failed on purpose.
      Usage: draw <subcommand>
        See 'draw --help' for more information.
      """)
  }

  func testError_ExitCodeIsSilent() {
    XCTAssertEqual(Paint.exitCode(for: ExitCode(3)), ExitCode(3))
    XCTAssertEqual(Paint.fullMessage(for: ExitCode.failure), "")
    XCTAssertEqual(ExitCode.validationFailure.rawValue, 64)
    XCTAssertEqual(ExitCode(rawValue: 0), .success)
    XCTAssertTrue(ExitCode.success.isSuccess)
  }

  func testError_OtherErrorsExitWithFailure() {
    struct DiskFull: Error, CustomStringConvertible {
      var description: String { "the disk is full" }
    }
    XCTAssertEqual(Paint.exitCode(for: DiskFull()), .failure)
    XCTAssertEqual(
      Paint.fullMessage(for: DiskFull()), "Error: the disk is full")
  }

  func testHelpRequest_ExitsCleanly() throws {
    for flag in ["--help", "-h"] {
      guard let error = parseError(Paint.self, ["s", "--bogus", flag]) else {
        return
      }
      XCTAssertEqual(Paint.exitCode(for: error), .success)
      XCTAssertEqual(Paint.fullMessage(for: error), Paint.helpMessage())
    }
    XCTAssertThrowsError(try Paint.parse(["--help"])) { error in
      XCTAssertEqual(Paint.message(for: error), Paint.helpMessage())
    }
  }

  func testCleanExit_Message() {
    XCTAssertEqual(Paint.fullMessage(for: CleanExit.message("done")), "done")
    XCTAssertEqual(Paint.exitCode(for: CleanExit.message("done")), .success)
  }

  func testVersion() {
    guard let error = parseError(Tools.self, ["--version"]) else { return }
    XCTAssertEqual(Tools.fullMessage(for: error), "1.2.3")
    XCTAssertEqual(Tools.exitCode(for: error), .success)
  }
}
