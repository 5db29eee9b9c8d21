import Foundation
import XCTest

@testable import Measurement
@testable import Course
@testable import Pipeline
@testable import FastEngine
@testable import FastKernels
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// `raytrace report --plot`: the SVG's marks read back, through the axes
/// each panel states, to the numbers of the rows they plot.
final class ErrorPlotTests: XCTestCase {
  /// Real rows: two scenes (one the naive method fails on) in both
  /// precisions, with the course engine's rows, and antialiasing rows.
  func measuredRows() throws -> ([AccuracyRow], [AntialiasingRow]) {
    let timing = AccuracyRow.Timing(
      width: 16, height: 16, threads: 1, runs: 1, rounds: 1)
    var rows: [AccuracyRow] = []
    var antialiasing: [AntialiasingRow] = []
    for name in ["spheres", "stiff/far-sphere-1e6"] {
      let scene = try SceneParser.parse(
        contentsOf: "\(ProjectFiles.projectFolder)/scenes/\(name).txt")
      for precision in Precision.allCases {
        rows += AccuracyRow.measure(
          scene, name: name, precision: precision,
          reference: .platformDefault, timing: timing)
      }
      antialiasing += AntialiasingRow.measure(
        scene, name: name, width: 4, height: 4, threads: 1, runs: 1)
    }
    return (rows, antialiasing)
  }

  func testPlot_MarksReadBackToTheRowsNumbers() throws {
    var (rows, antialiasing) = try measuredRows()
    XCTAssertEqual(rows.filter { $0.method == .course }.count, 2)
    // An exact row sits on the "0" line.
    rows[1].measurement.maxRelativeError = 0
    let svg = ErrorPlot.svg(rows: rows, antialiasing: antialiasing)
    let marks = PlottedMark.all(in: svg)
    XCTAssertEqual(marks.count, rows.count + antialiasing.count)
    let panels = PlottedPanel.all(in: svg)
    XCTAssertEqual(panels.map(\.name), ["error", "antialiasing"])
    // Positions are written to a hundredth of a pixel: half of one moves
    // a value by a factor 10^(0.005 · decades / pixels) of the axis
    // (`resolution`), with 1e-12 for the arithmetic of the mapping.
    func tolerance(_ axis: LogAxis) -> Double {
      let decadesPerPixel =
        (axis.highest - axis.lowest)
        / (axis.end - axis.start).magnitude
      return Foundation.pow(10, 0.005 * decadesPerPixel) - 1 + 1e-12
    }
    for (index, row) in rows.enumerated() {
      let mark = try XCTUnwrap(
        marks.first {
          $0.panel == "error" && $0.scene == row.scene
            && $0.method == row.method.name
            && $0.precision == row.precision.rawValue
        }, "\(row.scene) \(row.precision) \(row.method)")
      let panel = try XCTUnwrap(panels.first { $0.name == "error" })
      let time = panel.x.value(atPixel: mark.x)
      XCTAssertEqual(
        time / (row.seconds * 1000), 1, accuracy: tolerance(panel.x))
      if index == 1 {
        XCTAssertEqual(mark.y, try XCTUnwrap(panel.zeroY), accuracy: 0.005)
      } else {
        let error = panel.y.value(atPixel: mark.y)
        XCTAssertEqual(
          error / row.measurement.maxRelativeError, 1,
          accuracy: tolerance(panel.y),
          "\(row.scene) \(row.precision) \(row.method)")
      }
    }
    let panel = try XCTUnwrap(panels.first { $0.name == "antialiasing" })
    for row in antialiasing {
      let mark = try XCTUnwrap(
        marks.first {
          $0.panel == "antialiasing" && $0.scene == row.scene
            && $0.numbers == "\(row.samples)"
        })
      XCTAssertEqual(
        panel.x.value(atPixel: mark.x) / Double(row.samples), 1,
        accuracy: tolerance(panel.x))
      XCTAssertEqual(
        panel.y.value(atPixel: mark.y) / row.measurement.rootMeanSquare, 1,
        accuracy: tolerance(panel.y))
    }
  }

  /// Names with XML's special characters stay well formed, and a plot of
  /// no antialiasing rows has one panel.
  func testPlot_EscapesNamesAndLeavesOutAnEmptyPanel() throws {
    var (rows, _) = try measuredRows()
    rows = rows.map {
      var row = $0
      row.scene = "a<b>&\"c\""
      return row
    }
    let svg = ErrorPlot.svg(rows: rows, antialiasing: [])
    XCTAssertFalse(svg.contains("a<b>"))
    XCTAssertTrue(svg.contains("a&lt;b&gt;&amp;&quot;c&quot;"))
    XCTAssertEqual(PlottedPanel.all(in: svg).map(\.name), ["error"])
  }

  func testLogAxis_PixelAndValueAreInverse() {
    let axis = LogAxis(lowest: -16, highest: -4, start: 410, end: 48)
    XCTAssertEqual(axis.pixel(1e-16), 410)
    XCTAssertEqual(axis.pixel(1e-4), 48)
    for value in [3e-15, 1e-10, 7.5e-5] {
      XCTAssertEqual(
        axis.value(atPixel: axis.pixel(value)) / value, 1, accuracy: 1e-12)
    }
    XCTAssertEqual(LogAxis(attribute: axis.attribute), axis)
    XCTAssertEqual(axis.decades, -16 ... -4)
  }
}

/// A mark of the plot as the SVG writes it.
struct PlottedMark {
  var panel: String
  var scene: String
  var precision: String?
  var method: String?
  /// What it says it plots across (`data-x`).
  var numbers: String?
  var x: Double
  var y: Double

  /// Every `<g class="mark" …>` of `svg`, its place from its transform.
  static func all(in svg: String) -> [PlottedMark] {
    elements(in: svg, opening: "<g class=\"mark\"").compactMap { attributes in
      guard let panel = attributes["data-panel"],
        let scene = attributes["data-scene"],
        let transform = attributes["transform"],
        transform.hasPrefix("translate("), transform.hasSuffix(")")
      else { return nil }
      let numbers = transform.dropFirst(10).dropLast().split(separator: " ")
        .compactMap { Double($0) }
      guard numbers.count == 2 else { return nil }
      return PlottedMark(
        panel: panel, scene: scene, precision: attributes["data-precision"],
        method: attributes["data-method"], numbers: attributes["data-x"],
        x: numbers[0], y: numbers[1])
    }
  }
}

/// A panel of the plot and the axes it states.
struct PlottedPanel {
  var name: String
  var x: LogAxis
  var y: LogAxis
  var zeroY: Double?

  static func all(in svg: String) -> [PlottedPanel] {
    elements(in: svg, opening: "<g class=\"panel\"").compactMap { attributes in
      guard let name = attributes["data-panel"],
        let x = attributes["data-x-axis"].flatMap(LogAxis.init(attribute:)),
        let y = attributes["data-y-axis"].flatMap(LogAxis.init(attribute:))
      else { return nil }
      return PlottedPanel(
        name: name, x: x, y: y,
        zeroY: attributes["data-zero-y"].flatMap {
          Double($0)
        })
    }
  }
}

/// The attributes of each element of `svg` that starts with `opening`,
/// entities decoded.
private func elements(in svg: String, opening: String) -> [[String: String]] {
  svg.components(separatedBy: opening).dropFirst().map { rest in
    let tag = rest.prefix { $0 != ">" }
    var attributes: [String: String] = [:]
    for part in tag.components(separatedBy: "\" ") {
      let pair = part.split(separator: "=", maxSplits: 1)
      guard pair.count == 2 else { continue }
      let name = pair[0].trimmingCharacters(in: .whitespaces)
      let value = pair[1].trimmingCharacters(
        in: CharacterSet(charactersIn: "\""))
      attributes[name] =
        value
        .replacingOccurrences(of: "&quot;", with: "\"")
        .replacingOccurrences(of: "&apos;", with: "'")
        .replacingOccurrences(of: "&lt;", with: "<")
        .replacingOccurrences(of: "&gt;", with: ">")
        .replacingOccurrences(of: "&amp;", with: "&")
    }
    return attributes
  }
}
