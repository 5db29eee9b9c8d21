import ArgumentParser
import XCTest

final class ParsingTests: XCTestCase {
  func testParse_Defaults() throws {
    let command = try RenderLike.parse(["scene.txt"])
    XCTAssertEqual(command.scene, "scene.txt")
    XCTAssertNil(command.input)
    XCTAssertNil(command.output)
    XCTAssertEqual(command.size, [])
    XCTAssertEqual(command.precision, .double)
    XCTAssertNil(command.threads)
    XCTAssertEqual(command.pngLevel, 6)
    XCTAssertFalse(command.stats)
  }

  func testDefaults_ReadableBeforeParsing() {
    let command = RenderLike()
    XCTAssertEqual(command.pngLevel, 6)
    XCTAssertEqual(command.precision, .double)
    XCTAssertNil(command.scene)
  }

  func testParse_LongOption() throws {
    let command = try RenderLike.parse([
      "s", "--output", "a.png", "--threads", "4",
    ])
    XCTAssertEqual(command.output, "a.png")
    XCTAssertEqual(command.threads, 4)
  }

  func testParse_EqualsForm() throws {
    let command = try RenderLike.parse([
      "s", "--output=a=b.png", "--png-level=9", "-output=c.png",
    ])
    XCTAssertEqual(command.output, "c.png")
    XCTAssertEqual(command.pngLevel, 9)
    let first = try RenderLike.parse(["s", "--output=a=b.png"])
    XCTAssertEqual(first.output, "a=b.png")
  }

  func testParse_ShortOption() throws {
    let command = try RenderLike.parse(["s", "-o", "a.png"])
    XCTAssertEqual(command.output, "a.png")
  }

  func testParse_SingleDashLongOption() throws {
    let command = try RenderLike.parse([
      "-input", "scene.txt", "-output", "a.png", "-size", "64", "48",
    ])
    XCTAssertNil(command.scene)
    XCTAssertEqual(command.input, "scene.txt")
    XCTAssertEqual(command.output, "a.png")
    XCTAssertEqual(command.size, [64, 48])
  }

  func testParse_SingleAndDoubleDashDepthAreDifferentOptions() throws {
    let command = try RenderLike.parse([
      "s", "--depth", "d.png", "-depth", "1", "5", "e.pfm",
    ])
    XCTAssertEqual(command.depth, "d.png")
    XCTAssertEqual(command.assignmentDepth, ["1", "5", "e.pfm"])
  }

  func testParse_UpToNextOptionStopsAtNextOption() throws {
    let command = try RenderLike.parse([
      "--size", "640", "480", "-o", "a.png", "scene.txt",
    ])
    XCTAssertEqual(command.size, [640, 480])
    XCTAssertEqual(command.output, "a.png")
    XCTAssertEqual(command.scene, "scene.txt")
  }

  func testParse_UpToNextOptionStopsAtTerminator() throws {
    let command = try RenderLike.parse([
      "--size", "640", "480", "--", "-scene.txt",
    ])
    XCTAssertEqual(command.size, [640, 480])
    XCTAssertEqual(command.scene, "-scene.txt")
  }

  func testParse_ArrayValuesReplaceDefault() throws {
    struct Lucky: ParsableCommand {
      @Option(parsing: .upToNextOption) var numbers: [Int] = [7, 14]
      @Option var tag: [String] = ["a"]
    }
    let command = try Lucky.parse([
      "--numbers", "1", "--tag", "x", "--numbers", "2", "3", "--tag", "y",
    ])
    XCTAssertEqual(command.numbers, [1, 2, 3])
    XCTAssertEqual(command.tag, ["x", "y"])
    XCTAssertEqual(try Lucky.parse([]).numbers, [7, 14])
  }

  /// As in the real package, a token that starts with a dash is an option,
  /// never the value of a `.next` or `.upToNextOption` option: `-1` too.
  func testParse_DashValueIsAnOptionNotAValue() {
    for arguments in [
      ["s", "--shift", "-3"], ["s", "--depth-range", "-0.5", "1"],
      ["s", "-depth", "-1", "5", "d.pfm"],
    ] {
      XCTAssertThrowsError(try RenderLike.parse(arguments), "\(arguments)") {
        XCTAssertTrue(
          RenderLike.message(for: $0).hasPrefix("Missing value for '"),
          RenderLike.message(for: $0))
      }
    }
  }

  /// `.unconditional` and an attached value take a dash value, as in the
  /// real package; `.upToNextOption` goes on after an attached value.
  func testParse_UnconditionalOrAttachedDashValue() throws {
    struct Shifts: ParsableCommand {
      @Option(parsing: .unconditional) var shift = 0
      @Option(parsing: .unconditionalSingleValue) var offsets: [Int] = []
      @Option(parsing: .upToNextOption) var range: [Double] = []
    }
    let command = try Shifts.parse([
      "--shift", "-3", "--offsets", "-1", "--offsets", "-2", "--range=-0.5",
      "4",
    ])
    XCTAssertEqual(command.shift, -3)
    XCTAssertEqual(command.offsets, [-1, -2])
    XCTAssertEqual(command.range, [-0.5, 4])
  }

  func testParse_DeclaredNameLikeNumberIsAnOption() throws {
    struct Digits: ParsableCommand {
      @Flag(name: .customShort("1")) var one = false
      @Option(parsing: .upToNextOption) var values: [Int] = []
    }
    let command = try Digits.parse(["--values", "2", "-1"])
    XCTAssertEqual(command.values, [2])
    XCTAssertTrue(command.one)
  }

  func testParse_EnumChoice() throws {
    XCTAssertEqual(
      try RenderLike.parse(["s", "--precision", "float"]).precision, .float)
  }

  func testParse_RepeatedSingleValueOptionKeepsLast() throws {
    XCTAssertEqual(
      try RenderLike.parse(["s", "-o", "a.png", "--output", "b.png"]).output,
      "b.png")
  }

  func testParse_Flag() throws {
    XCTAssertTrue(try RenderLike.parse(["s", "--stats"]).stats)
  }

  func testParse_CountingFlagAndShortGroup() throws {
    struct Verbose: ParsableCommand {
      @Flag(name: .short) var verbose: Int
      @Flag(name: .short) var quiet = false
    }
    let command = try Verbose.parse(["-vvq", "-v"])
    XCTAssertEqual(command.verbose, 3)
    XCTAssertTrue(command.quiet)
    XCTAssertEqual(try Verbose.parse([]).verbose, 0)
  }

  func testParse_SingleDashLongNameIsNotAShortGroup() throws {
    struct Letters: ParsableCommand {
      @Flag(name: .customShort("i")) var i = false
      @Flag(name: .customShort("n")) var n = false
      @Option(name: .customLong("in", withSingleDash: true)) var input: String?
    }
    let whole = try Letters.parse(["-in", "x"])
    XCTAssertEqual(whole.input, "x")
    XCTAssertFalse(whole.i)
    XCTAssertFalse(whole.n)
    let group = try Letters.parse(["-ni"])
    XCTAssertTrue(group.i)
    XCTAssertTrue(group.n)
    XCTAssertNil(group.input)
  }

  func testParse_InvertedFlag() throws {
    struct Colour: ParsableCommand {
      @Flag(inversion: .prefixedNo) var colour = true
    }
    XCTAssertTrue(try Colour.parse([]).colour)
    XCTAssertFalse(try Colour.parse(["--no-colour"]).colour)
    XCTAssertTrue(try Colour.parse(["--no-colour", "--colour"]).colour)
  }

  func testParse_KebabCaseDefaultNames() throws {
    struct Names: ParsableCommand {
      @Option var pngLevel = 6
      @Option var maxURLLength = 10
      @Argument var inputFile: String
    }
    let command = try Names.parse([
      "--png-level", "3", "--max-url-length", "4", "f",
    ])
    XCTAssertEqual(command.pngLevel, 3)
    XCTAssertEqual(command.maxURLLength, 4)
    XCTAssertEqual(command.inputFile, "f")
  }

  func testParse_PositionalArray() throws {
    let command = try Report.parse(["a.txt", "--runs", "2", "b.txt"])
    XCTAssertEqual(command.scenes, ["a.txt", "b.txt"])
    XCTAssertEqual(command.runs, 2)
  }

  func testParse_OtherStrategies() throws {
    struct Strategies: ParsableCommand {
      @Option(parsing: .unconditional) var raw: String?
      @Option(parsing: .scanningForValue) var scanned: String?
      @Option(name: .customShort("I", allowingJoined: true)) var include:
        [String] = []
      @Option(parsing: .remaining) var rest: [String] = []
      @Flag var flag = false
    }
    let command = try Strategies.parse(
      [
        "--raw", "--flag", "--scanned", "--flag", "value", "-Ia", "-I", "b",
        "--rest", "-x", "--y",
      ])
    XCTAssertEqual(command.raw, "--flag")
    XCTAssertEqual(command.scanned, "value")
    XCTAssertTrue(command.flag)
    XCTAssertEqual(command.include, ["a", "b"])
    XCTAssertEqual(command.rest, ["-x", "--y"])
  }

  func testParse_OptionGroupIsSharedAndValidated() throws {
    struct Common: ParsableArguments {
      @Option var threads = 1
      mutating func validate() throws {
        guard threads >= 1 else {
          throw ValidationError("--threads must be at least 1.")
        }
      }
    }
    struct Job: ParsableCommand {
      @OptionGroup var common: Common
      @Flag var fast = false
    }
    let command = try Job.parse(["--threads", "3", "--fast"])
    XCTAssertEqual(command.common.threads, 3)
    XCTAssertTrue(command.fast)
    XCTAssertThrowsError(try Job.parse(["--threads", "0"])) { error in
      XCTAssertEqual(Job.message(for: error), "--threads must be at least 1.")
    }
  }

  func testParse_ParsableArguments() throws {
    struct Options: ParsableArguments {
      @Option var name: String
    }
    XCTAssertEqual(try Options.parse(["--name", "x"]).name, "x")
  }

  func testParse_PositionalStrategies() throws {
    struct Passthrough: ParsableCommand {
      @Argument var tool: String
      @Argument(parsing: .postTerminator) var toolArguments: [String] = []
      @Flag var verbose = false
    }
    let command = try Passthrough.parse([
      "--verbose", "cc", "--", "-O2", "--verbose",
    ])
    XCTAssertEqual(command.tool, "cc")
    XCTAssertEqual(command.toolArguments, ["-O2", "--verbose"])
    XCTAssertTrue(command.verbose)

    struct Collect: ParsableCommand {
      @Flag var known = false
      @Argument(parsing: .allUnrecognized) var rest: [String] = []
    }
    let collected = try Collect.parse(["a", "--other", "--known", "-x", "b"])
    XCTAssertEqual(collected.rest, ["a", "--other", "-x", "b"])
    XCTAssertTrue(collected.known)
  }

  func testParse_ExclusiveFlag() throws {
    struct Exclusive: ParsableCommand {
      @Flag(inversion: .prefixedEnableDisable, exclusivity: .exclusive)
      var cache = true
    }
    XCTAssertFalse(try Exclusive.parse(["--disable-cache"]).cache)
    XCTAssertThrowsError(
      try Exclusive.parse(["--enable-cache", "--disable-cache"])
    ) { error in
      XCTAssertEqual(
        Exclusive.message(for: error),
        "Value to be set with flag '--disable-cache' had already been set with flag '--enable-cache'"
      )
    }
  }

  func testParsedCommands_HaveValueSemantics() throws {
    let first = try RenderLike.parse(["s", "--threads", "2"])
    var second = first
    second.threads = 8
    XCTAssertEqual(first.threads, 2)
    XCTAssertEqual(second.threads, 8)
  }

  func testExpressibleByArgument_Conformances() {
    XCTAssertEqual(Int(argument: "-12"), -12)
    XCTAssertNil(Int(argument: "0x10"))
    XCTAssertEqual(Double(argument: "2.5"), 2.5)
    XCTAssertEqual(Float(argument: "0.5"), 0.5)
    XCTAssertEqual(String(argument: "x"), "x")
    XCTAssertEqual(Finish(argument: "gloss"), .gloss)
    XCTAssertNil(Finish(argument: "Gloss"))
    XCTAssertEqual(Finish.allValueStrings, ["matte", "gloss"])
    XCTAssertEqual(Finish.gloss.defaultValueDescription, "gloss")
    XCTAssertEqual(2.5.defaultValueDescription, "2.5")
    XCTAssertEqual(Int.allValueStrings, [])
  }
}
