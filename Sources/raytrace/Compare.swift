import ArgumentParser
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// `raytrace compare A B`: how far two images are apart, where, and the
/// mistake it looks like.
struct Compare: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "compare",
    abstract: "Compare two images: how many pixels differ, where, and why.",
    discussion: """
      A and B are PNG, PPM, PFM, NPY or BMP files of the same size (8-bit \
      or raw values), told apart by content. A pixel matches when every \
      channel is within --tolerance. It prints the share of matching \
      pixels, the largest difference and where it is, and the pattern of \
      the differences: a shift by a pixel, flipped rows or columns, swapped \
      channels, the two normal conventions (|n| and (n + 1)/2), a constant \
      offset, or else whether they lie on silhouettes, in one region or \
      everywhere.

      Exit status: 0 when the share meets --need, 1 when it does not (or \
      the sizes differ), 2 when an image cannot be read, 64 for a bad \
      command line.
      """)

  @Argument(help: "The first image (the reference).")
  var a: String

  @Argument(help: "The second image.")
  var b: String

  @Option(
    help: ArgumentHelp(
      """
        How far a channel may differ: levels for 8-bit images (default 2), \
        relative difference for raw values (default 1e-6).
        """,
      valueName: "levels"))
  var tolerance: Double?

  @Option(
    help: ArgumentHelp(
      "The share of pixels that must match, in percent (default 99.9).",
      valueName: "percent"))
  var need: Double = 99.9

  @Option(
    help: ArgumentHelp(
      "Write a picture of the differences (a heat map over a dimmed A).",
      valueName: "file.png"))
  var diff: String?

  mutating func validate() throws {
    guard !Raytrace.defersValidation else { return }
    if let tolerance, !(tolerance >= 0 && tolerance.isFinite) {
      throw ValidationError(
        "--tolerance must be a number ≥ 0; got \(tolerance).")
    }
    guard need >= 0 && need <= 100 else {
      throw ValidationError("--need must be between 0 and 100; got \(need).")
    }
    if let diff {
      guard ImageFormat(path: diff)?.isEightBit == true else {
        throw ValidationError(
          "--diff writes an 8-bit image: give it a .png or .ppm name.")
      }
      guard !FileIdentity.same(diff, a) && !FileIdentity.same(diff, b) else {
        throw ValidationError("--diff would replace one of the images.")
      }
    }
  }

  func run() throws {
    let first: ReadImage
    let second: ReadImage
    do {
      first = try ImageFileReader.read(contentsOf: a)
      second = try ImageFileReader.read(contentsOf: b)
    } catch {
      let path = (try? ImageFileReader.read(contentsOf: a)) == nil ? a : b
      printError("raytrace: error: cannot read '\(path)': \(error)")
      throw ExitCode(2)
    }
    guard first.width == second.width, first.height == second.height,
      first.channels == second.channels
    else {
      printError(
        "raytrace: error: \(a) is \(Self.size(first)) and \(b) is "
          + "\(Self.size(second)): there is nothing to compare pixel by pixel")
      throw ExitCode.failure
    }
    let comparison = ImageComparison(
      first, second,
      tolerance: tolerance
        ?? ImageComparison.defaultTolerance(
          eightBit: first.isEightBit && second.isEightBit))
    for line in comparison.report(a, b, need: need / 100) {
      printOutput(line)
    }
    if let diff {
      let image = comparison.differenceImage(first, second)
      let bytes =
        ImageFormat(path: diff) == .png
        ? PNGEncoder.encode(image) : PPMEncoder.encode(image)
      do {
        try AtomicFile.write(bytes, to: diff)
      } catch {
        printError("raytrace: error: \(error)")
        throw ExitCode(2)
      }
    }
    if comparison.share < need / 100 { throw ExitCode.failure }
  }

  static func size(_ image: ReadImage) -> String {
    "\(image.width)×\(image.height)"
      + (image.channels == 3 ? "" : " with \(image.channels) channel")
  }
}
