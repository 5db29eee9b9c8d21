import XCTest

@testable import Measurement
@testable import Course
@testable import Pipeline
@testable import FastEngine
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import FastEngine
@testable import PlatformSupport
import TestSupport

/// Each kind of difference `raytrace compare` names, recognised on small
/// made-up images: a disc of normals on a black background, as the course
/// style draws a normals image, changed the way a student's mistake would.
final class ImageComparisonTests: XCTestCase {
  static let (width, height) = (40, 30)

  /// A sphere's normals as |n|·255 (the course style), misses black; or as
  /// (n + 1)/2·255 (the mit style), misses grey.
  static func normals(absolute: Bool = true) -> ReadImage {
    var values: [Double] = []
    for row in 0..<height {
      for column in 0..<width {
        let x = (Double(column) + 0.5 - 18) / 11
        let y = (13 - Double(row) - 0.5) / 11
        let squared = x * x + y * y
        let n =
          squared < 1 ? [x, y, (1 - squared).squareRoot()] : [0.0, 0, 0]
        for value in n {
          values.append(
            absolute
              ? (abs(value) * 255).rounded(.down)
              : ((value + 1) / 2 * 255).rounded())
        }
      }
    }
    return ReadImage(
      width: width, height: height, channels: 3, values: values,
      isEightBit: true)
  }

  func pattern(_ a: ReadImage, _ b: ReadImage) -> ImageComparison.Pattern {
    ImageComparison(a, b, tolerance: 2).pattern
  }

  func changed(_ image: ReadImage, _ value: (Int, Int, Int) -> Double)
    -> ReadImage
  {
    var copy = image
    for row in 0..<image.height {
      for column in 0..<image.width {
        for channel in 0..<3 {
          copy.values[(row * image.width + column) * 3 + channel] = value(
            column, row, channel)
        }
      }
    }
    return copy
  }

  func testIdentical_AndWithinTolerance() {
    let a = Self.normals()
    XCTAssertEqual(pattern(a, a), .identical)
    let brighter = changed(a) { min(255, a[$0, $1, $2] + 1) }
    let comparison = ImageComparison(a, brighter, tolerance: 2)
    XCTAssertEqual(comparison.pattern, .withinTolerance)
    XCTAssertEqual(comparison.share, 1)
    XCTAssertNil(comparison.first)
  }

  func testShift_ByOneRowOrColumn() {
    let a = Self.normals()
    let down = changed(a) { column, row, channel in
      row == 0 ? 0 : a[column, row - 1, channel]
    }
    XCTAssertEqual(pattern(a, down), .shifted(x: 0, y: 1))
    let left = changed(a) { column, row, channel in
      column == Self.width - 1 ? 0 : a[column + 1, row, channel]
    }
    XCTAssertEqual(pattern(a, left), .shifted(x: -1, y: 0))
  }

  func testFlips() {
    let a = Self.normals()
    XCTAssertEqual(
      pattern(a, changed(a) { a[$0, Self.height - 1 - $1, $2] }), .flippedRows)
    XCTAssertEqual(
      pattern(a, changed(a) { a[Self.width - 1 - $0, $1, $2] }),
      .flippedColumns)
  }

  func testSwappedChannels() {
    let a = Self.normals()
    // B's red holds A's blue and B's blue A's red.
    let swapped = changed(a) { column, row, channel in
      a[column, row, [2, 1, 0][channel]]
    }
    XCTAssertEqual(pattern(a, swapped), .swappedChannels(order: [2, 1, 0]))
  }

  /// A transform that changes nothing where the images differ does not
  /// explain them: one pixel off in a grey image is not "channels
  /// swapped" (swapping changes nothing in grey), and a pixel off in an
  /// image symmetric left to right is not "mirrored".
  func testOnePixelOff_IsNotATransform() {
    let grey = changed(Self.normals()) { column, row, _ in
      Double((column * 7 + row * 3) % 256)
    }
    let symmetric = changed(Self.normals()) { column, row, _ in
      Double(min(column, Self.width - 1 - column) * 9 + row)
    }
    for a in [grey, symmetric] {
      let b = changed(a) { column, row, channel in
        column == 5 && row == 6
          ? 255 - a[column, row, channel]
          : a[column, row, channel]
      }
      switch pattern(a, b) {
      case .swappedChannels, .flippedColumns, .flippedRows, .shifted,
        .normalConvention:
        XCTFail("\(pattern(a, b)) for one pixel off")
      default: break
      }
    }
  }

  /// |n| against (n + 1)/2, whichever is A: told apart from a real error.
  func testNormalConvention_EitherWay() {
    let absolute = Self.normals(absolute: true)
    let shifted = Self.normals(absolute: false)
    XCTAssertEqual(
      pattern(absolute, shifted), .normalConvention(aIsAbsolute: true))
    XCTAssertEqual(
      pattern(shifted, absolute), .normalConvention(aIsAbsolute: false))
  }

  func testOffset_ClampedAt255() {
    let a = Self.normals()
    let brighter = changed(a) { min(255, a[$0, $1, $2] + 20) }
    XCTAssertEqual(pattern(a, brighter), .offset([20, 20, 20]))
  }

  /// A disc one pixel larger differs only along its edge.
  func testSilhouettes() {
    let a = Self.normals()
    let larger = changed(a) { column, row, channel in
      let x = (Double(column) + 0.5 - 18) / 11
      let y = (13 - Double(row) - 0.5) / 11
      let r = (x * x + y * y).squareRoot()
      return r >= 1 && r < 1.09 ? 200 : a[column, row, channel]
    }
    guard case .silhouettes(let share) = pattern(a, larger) else {
      return XCTFail("\(pattern(a, larger))")
    }
    XCTAssertGreaterThanOrEqual(share, 0.8)
  }

  func testRegion() {
    let a = Self.normals()
    let patched = changed(a) { column, row, channel in
      (12...17).contains(column) && (10...14).contains(row)
        ? 255 - a[column, row, channel] : a[column, row, channel]
    }
    XCTAssertEqual(
      pattern(a, patched), .region(columns: 12...17, rows: 10...14))
  }

  func testEverywhere_AndTheLargestDifference() {
    let a = Self.normals()
    var generator = SplitMix64(seed: 9)
    let noisy = changed(a) { column, row, channel in
      column == 3 && row == 4 && channel == 1
        ? 250 : Double(Int.random(in: 0...255, using: &generator))
    }
    let comparison = ImageComparison(a, noisy, tolerance: 2)
    XCTAssertEqual(comparison.pattern, .everywhere)
    XCTAssertLessThan(comparison.share, 0.1)
    XCTAssertEqual(comparison.largest?.difference, 255)
    XCTAssertEqual(comparison.first?.row, 0)
  }

  /// Raw values: a relative tolerance, infinities of one sign alike.
  func testRawValues_RelativeTolerance() {
    let a = ReadImage(
      width: 3, height: 1, channels: 1, values: [1, .infinity, 1e-300],
      isEightBit: false)
    var b = a
    b.values[0] = 1 + 5e-7
    b.values[2] = 1e-300 * (1 + 5e-7)
    XCTAssertEqual(ImageComparison(a, b, tolerance: 1e-6).share, 1)
    b.values[0] = 1 + 2e-6
    let comparison = ImageComparison(a, b, tolerance: 1e-6)
    XCTAssertEqual(comparison.differingPixels, 1)
    XCTAssertEqual(comparison.largest?.column, 0)
    b.values[1] = -.infinity
    XCTAssertEqual(ImageComparison(a, b, tolerance: 1e-6).differingPixels, 2)
  }

  /// The report's lines: the share and verdict, the largest difference
  /// and where, the pattern.
  func testReport() {
    let a = Self.normals()
    let b = changed(a) { a[$0, Self.height - 1 - $1, $2] }
    let lines = ImageComparison(a, b, tolerance: 2).report(
      "a.png", "b.png", need: 0.999)
    XCTAssertEqual(lines.count, 4)
    XCTAssertEqual(lines[0], "a.png and b.png: 40×30, 8-bit")
    XCTAssertTrue(lines[1].hasSuffix("needs 99.9 %: FAIL"), lines[1])
    XCTAssertTrue(lines[2].hasPrefix("largest difference: "), lines[2])
    XCTAssertTrue(lines[3].contains("upside down"), lines[3])
  }

  /// The picture of the differences: heat where they differ, A dimmed
  /// elsewhere.
  func testDifferenceImage() {
    let a = Self.normals()
    let b = changed(a) { column, row, channel in
      column == 5 && row == 6
        ? 255 - a[column, row, channel] : a[column, row, channel]
    }
    let comparison = ImageComparison(a, b, tolerance: 2)
    let image = comparison.differenceImage(a, b)
    XCTAssertEqual(image[5, 6].0, 255)
    XCTAssertEqual(image[5, 6].2, 0)
    let (r, g, bl) = image[18, 13]
    XCTAssertTrue(r == g && g == bl && r < 100, "dimmed grey: \(r) \(g) \(bl)")
  }
}
