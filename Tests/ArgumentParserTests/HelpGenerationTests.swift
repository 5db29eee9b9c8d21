import ArgumentParser
import XCTest

final class HelpGenerationTests: XCTestCase {
  static let paintOptions = """
    ARGUMENTS:
      <scene>                 The scene file.

    OPTIONS:
      -o, --output, -output <file>
                              Write the image to this file.
      --size, -size <w h>     Width and height.
      --finish <finish>       The surface finish. (values: matte, gloss; default:
                              matte)
      --png-level <png-level> zlib level for PNG files, 0 to 9: lower is faster and
                              larger, higher smaller and slower. (default: 6)
      --stats                 Print statistics.
      -h, --help              Show help information.

    """

  func testHelp_SmallCommand() {
    XCTAssertEqual(
      Paint.helpMessage(),
      """
      OVERVIEW: Paint a scene.

      Reads the scene and writes an image.

      USAGE: paint <scene> [--output <file>] [--size <w h> ...] [--finish <finish>] [--png-level <png-level>] [--stats]


      """ + Self.paintOptions)
  }

  func testHelp_RootWithDefaultSubcommand() {
    XCTAssertEqual(
      Draw.helpMessage(),
      """
      OVERVIEW: Draw things.

      USAGE: draw <subcommand>

      OPTIONS:
        -h, --help              Show help information.

      SUBCOMMANDS:
        paint (default)         Paint a scene.
        report                  Measure things.

        See 'draw help <subcommand>' for detailed help.
      """)
  }

  func testHelp_Subcommand() {
    XCTAssertEqual(
      Draw.helpMessage(for: Paint.self),
      """
      OVERVIEW: Paint a scene.

      Reads the scene and writes an image.

      USAGE: draw paint <scene> [--output <file>] [--size <w h> ...] [--finish <finish>] [--png-level <png-level>] [--stats]


      """ + Self.paintOptions)
    XCTAssertEqual(
      Draw.helpMessage(for: Report.self),
      """
      OVERVIEW: Measure things.

      USAGE: draw report [<scenes> ...] [--runs <runs>]

      ARGUMENTS:
        <scenes>                Scene files.

      OPTIONS:
        --runs <runs>           Timed renders per row. (default: 5)
        -h, --help              Show help information.

      """)
  }

  func testHelp_VersionAndNoAbstract() {
    XCTAssertEqual(
      Tools.helpMessage(),
      """
      USAGE: tools <subcommand>

      OPTIONS:
        --version               Show the version.
        -h, --help              Show help information.

      SUBCOMMANDS:
        report                  Measure things.

        See 'tools help <subcommand>' for detailed help.
      """)
  }

  func testHelp_ManyOptionsShortenUsage() {
    struct Many: ParsableCommand {
      @Argument var file: String
      @Option var a: Int?
      @Option var b: Int?
      @Option var c: Int?
      @Option var d: Int?
      @Option var e: Int?
      @Option var f: Int?
      @Option var g: Int?
      @Option var h2: Int?
      @Option var i: Int?
      @Option var j: Int?
      @Option var k: Int?
      @Option var l: Int?
    }
    XCTAssertTrue(
      Many.helpMessage().hasPrefix("USAGE: many [<options>] <file>\n\n"))
  }

  func testHelp_HiddenFlagInversionAndDiscussion() {
    struct Shade: ParsableCommand {
      @Flag(inversion: .prefixedNo, help: "Use colour.") var colour = true
      @Option(
        help: ArgumentHelp(
          "The gamma.", discussion: "Applied after tone mapping."))
      var gamma: Double = 2.2
      @Option(help: .hidden) var secret: String?
    }
    let expected = """
      USAGE: shade [--colour] [--no-colour] [--gamma <gamma>]

      OPTIONS:
        --colour/--no-colour    Use colour. (default: --colour)
        --gamma <gamma>         The gamma. (default: 2.2)
              Applied after tone mapping.
        -h, --help              Show help information.

      """
    XCTAssertEqual(Shade.helpMessage(), expected)
    XCTAssertTrue(
      Shade.helpMessage(includeHidden: true).contains("  --secret <secret>\n"))
  }

  func testHelp_WrapsToColumns() {
    struct Narrow: ParsableCommand {
      @Flag(help: "One two three four five six.") var flag = false
    }
    XCTAssertEqual(
      Narrow.helpMessage(columns: 40),
      """
      USAGE: narrow [--flag]

      OPTIONS:
        --flag                  One two three
                                four five six.
        -h, --help              Show help
                                information.

      """)
  }
}
