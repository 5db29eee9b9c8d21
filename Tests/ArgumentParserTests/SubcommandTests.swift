import ArgumentParser
import XCTest

final class SubcommandTests: XCTestCase {
  func testDispatch_NamedSubcommand() throws {
    let command = try Draw.parseAsRoot(["report", "a.txt", "--runs", "3"])
    let report = try XCTUnwrap(command as? Report)
    XCTAssertEqual(report.scenes, ["a.txt"])
    XCTAssertEqual(report.runs, 3)
  }

  func testDispatch_DefaultSubcommand() throws {
    let command = try Draw.parseAsRoot(["scene.txt", "-o", "a.png"])
    let paint = try XCTUnwrap(command as? Paint)
    XCTAssertEqual(paint.scene, "scene.txt")
    XCTAssertEqual(paint.output, "a.png")
  }

  func testDispatch_DefaultSubcommandWithSingleDashOptionsFirst() throws {
    let command = try Draw.parseAsRoot([
      "-size", "3", "4", "-output", "a.png", "report",
    ])
    let paint = try XCTUnwrap(command as? Paint)
    XCTAssertEqual(paint.scene, "report")
    XCTAssertEqual(paint.size, [3, 4])
  }

  func testDispatch_ExplicitDefaultSubcommand() throws {
    let paint = try XCTUnwrap(
      try Draw.parseAsRoot(["paint", "scene.txt"]) as? Paint)
    XCTAssertEqual(paint.scene, "scene.txt")
  }

  func testDispatch_HiddenSubcommandStillRuns() throws {
    XCTAssertTrue(try Draw.parseAsRoot(["bench"]) is Bench)
  }

  func testDispatch_Alias() throws {
    struct Shade: ParsableCommand {
      static let configuration = CommandConfiguration(
        abstract: "Shade.", aliases: ["sh"])
      @Flag var fast = false
    }
    struct Studio: ParsableCommand {
      static let configuration = CommandConfiguration(subcommands: [Shade.self])
    }
    let shade = try XCTUnwrap(
      try Studio.parseAsRoot(["sh", "--fast"]) as? Shade)
    XCTAssertTrue(shade.fast)
    XCTAssertTrue(
      Studio.helpMessage().contains("\n  shade, sh               Shade.\n"))
  }

  func testHelp_ForRootAndSubcommands() throws {
    let cases: [([String], String)] = [
      (["--help"], Draw.helpMessage()),
      (["-h"], Draw.helpMessage()),
      (["help"], Draw.helpMessage()),
      (["paint", "--help"], Draw.helpMessage(for: Paint.self)),
      (["help", "paint"], Draw.helpMessage(for: Paint.self)),
      (["report", "-h"], Draw.helpMessage(for: Report.self)),
      // As in the real package: a help flag before the default subcommand
      // is the root's only when it is the one argument.
      (["scene.txt", "--help"], Draw.helpMessage(for: Paint.self)),
      (["--help", "scene.txt"], Draw.helpMessage(for: Paint.self)),
      (["scene.txt", "--frob", "-h"], Draw.helpMessage(for: Paint.self)),
      (["help", "report"], Draw.helpMessage(for: Report.self)),
    ]
    for (arguments, expected) in cases {
      var command = try Draw.parseAsRoot(arguments)
      XCTAssertThrowsError(try command.run(), "\(arguments)") { error in
        XCTAssertEqual(Draw.fullMessage(for: error), expected, "\(arguments)")
        XCTAssertEqual(Draw.exitCode(for: error), .success, "\(arguments)")
      }
    }
  }

  func testErrors_InSubcommandShowSubcommandUsage() throws {
    do {
      _ = try Draw.parseAsRoot(["paint", "s", "--finish", "shiny"])
      XCTFail("Expected an error")
    } catch {
      XCTAssertEqual(
        Draw.fullMessage(for: error),
        """
        Error: The value 'shiny' is invalid for '--finish <finish>'. Please provide one of 'matte' and 'gloss'.
        Help:  --finish <finish>  The surface finish.
        Usage: draw paint <scene> [--output <file>] [--size <w h> ...] [--finish <finish>] [--png-level <png-level>] [--stats]
          See 'draw paint --help' for more information.
        """)
    }
  }

  func testErrors_DefaultSubcommandUsageOnEmptyLine() throws {
    do {
      _ = try Draw.parseAsRoot([])
      XCTFail("Expected an error")
    } catch {
      XCTAssertEqual(
        Draw.message(for: error), "Missing expected argument '<scene>'")
      XCTAssertTrue(
        Draw.fullMessage(for: error).hasSuffix("\n\n" + Draw.helpMessage()))
    }
  }

  func testRootWithoutDefault_RunsShowHelp() throws {
    var command = try Tools.parseAsRoot([])
    XCTAssertThrowsError(try command.run()) { error in
      XCTAssertEqual(Tools.fullMessage(for: error), Tools.helpMessage())
      XCTAssertEqual(Tools.exitCode(for: error), .success)
    }
  }

  func testRootWithoutDefault_RejectsUnknownSubcommand() {
    XCTAssertThrowsError(try Tools.parseAsRoot(["frob"])) { error in
      XCTAssertEqual(Tools.message(for: error), "Unexpected argument 'frob'")
    }
  }

  func testParse_RootTypeRejectsSubcommandResult() {
    XCTAssertThrowsError(try Draw.parse(["report"]))
  }
}
