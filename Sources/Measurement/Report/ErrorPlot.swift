
/// `raytrace report --plot FILE.svg`: error against run time, as a
/// picture.
///
/// The first panel has one point per scene × precision × method: the render
/// time of one image (ms) across, the largest relative error of t
/// (|t − t_ref| / t_ref) up, both on log scales. Colour tells the precision
/// (float blue, double orange) and shape the method (naive a circle,
/// stable a square); the course engine, the student's code, is a green
/// triangle. A line joins each scene's naive and stable points in one
/// precision, so the price of exactness reads as the line's slope; a ring
/// marks a row where some pixels hit in one render and missed in the
/// reference. The second panel shows antialiasing: the RMS error of the
/// shaded image against samples per pixel, one line per scene, with the
/// 1/√N of independent samples drawn for reference.
///
/// Every point is a group of class `mark` carrying its numbers
/// (`data-x`, `data-y`, scene, precision, method) and placed by
/// `transform="translate(x y)"`; each panel states its axes
/// (`data-x-axis`, `data-y-axis`: see `LogAxis.attribute`), so a reader
/// can map the marks back to the numbers.
package enum ErrorPlot {
  static let height = 540.0
  static let errorWidth = 640.0
  static let antialiasingWidth = 420.0

  static let float = "#1f77b4"
  static let double = "#d95f02"
  static let course = "#1b9e77"
  static let sceneColours = [
    "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666",
  ]

  /// The SVG document of `rows` and, when there are any, `antialiasing`.
  package static func svg(
    rows: [AccuracyRow], antialiasing: [AntialiasingRow]
  ) -> String {
    let width = errorWidth + (antialiasing.isEmpty ? 0 : antialiasingWidth)
    var svg = [
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>",
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"\(Int(width))\" "
        + "height=\"\(Int(height))\" viewBox=\"0 0 \(Int(width)) "
        + "\(Int(height))\" font-family=\"Helvetica, Arial, sans-serif\">",
      "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>",
    ]
    svg += errorPanel(rows)
    if !antialiasing.isEmpty {
      svg += antialiasingPanel(antialiasing, left: errorWidth)
    }
    svg.append("</svg>")
    return svg.joined(separator: "\n") + "\n"
  }

  static func colour(_ row: AccuracyRow) -> String {
    switch (row.method, row.precision) {
    case (.course, _): course
    case (_, .float): float
    case (_, .double): double
    }
  }

  /// The first panel: error of t against time.
  static func errorPanel(_ rows: [AccuracyRow]) -> [String] {
    let panel = PlotPanel(
      left: 90, right: errorWidth - 24, top: 48, bottom: height - 130,
      x: LogAxis.decades(around: rows.map { $0.seconds * 1000 }),
      ys: rows.map(\.measurement.maxRelativeError))
    var svg = panel.open(
      name: "error", title: "Error against run time",
      xLabel: "render time of one image (ms, log scale)",
      yLabel: "largest relative error of t, |t − t_ref| / t_ref")
    func at(_ row: AccuracyRow) -> (x: Double, y: Double) {
      panel.point(row.seconds * 1000, row.measurement.maxRelativeError)
    }
    // Each scene's naive and stable joined, its course point dotted to
    // its stable one, under the marks.
    for row in rows where row.method != .fast(.naive) {
      let partner: ReportedMethod =
        row.method == .course ? .fast(.stable) : .fast(.naive)
      guard
        let other = rows.first(where: {
          $0.scene == row.scene && $0.method == partner
            && $0.precision == row.precision
        })
      else { continue }
      let (a, b) = (at(row), at(other))
      svg.append(
        panel.line(
          a.x, a.y, b.x, b.y, colour: colour(row), width: 1.2,
          dash: row.method == .course ? "2 3" : nil, opacity: 0.5))
    }
    for method in [ReportedMethod.fast(.naive), .fast(.stable), .course] {
      for row in rows where row.method == method {
        svg.append(mark(row, at: at(row)))
      }
    }
    svg.append(panel.close())
    svg += legend(top: height - 72)
    return svg
  }

  /// The mark of one row: its shape, colour, ring and numbers.
  static func mark(_ row: AccuracyRow, at point: (x: Double, y: Double))
    -> String
  {
    let n = SVGText.number
    let m = row.measurement
    let title =
      "\(row.scene), \(row.precision.rawValue), \(row.method.name): "
      + "\(row.seconds * 1000) ms, error \(m.maxRelativeError)"
      + (m.disagreements > 0 ? ", \(m.disagreements) hit/miss" : "")
    var element =
      "<g class=\"mark\" data-panel=\"error\" "
      + "data-scene=\"\(SVGText.escaped(row.scene))\" "
      + "data-precision=\"\(row.precision.rawValue)\" "
      + "data-method=\"\(row.method.name)\" "
      + "data-x=\"\(row.seconds * 1000)\" data-y=\"\(m.maxRelativeError)\" "
      + "transform=\"translate(\(n(point.x)) \(n(point.y)))\">"
      + "<title>\(SVGText.escaped(title))</title>"
    element += shape(row.method, colour: colour(row))
    if m.disagreements > 0 {
      element +=
        "<circle r=\"7.5\" fill=\"none\" stroke=\"\(colour(row))\" "
        + "stroke-width=\"1.2\"/>"
    }
    return element + "</g>"
  }

  /// A circle for naive, a square for stable, a triangle for the course
  /// engine, centred on (0, 0).
  static func shape(_ method: ReportedMethod, colour: String) -> String {
    switch method {
    case .fast(.naive):
      "<circle r=\"4.5\" fill=\"\(colour)\"/>"
    case .fast(.stable):
      "<rect x=\"-4\" y=\"-4\" width=\"8\" height=\"8\" fill=\"\(colour)\"/>"
    case .course:
      "<path d=\"M0,-5.5 L5,3.5 L-5,3.5 Z\" fill=\"\(colour)\"/>"
    }
  }

  /// The key below the first panel.
  static func legend(top: Double) -> [String] {
    let entries: [(ReportedMethod, String, String)] = [
      (.fast(.naive), float, "float, naive"),
      (.fast(.stable), float, "float, stable"),
      (.fast(.naive), double, "double, naive"),
      (.fast(.stable), double, "double, stable"),
      (.course, course, "course engine (double)"),
    ]
    var svg: [String] = []
    var x = 40.0
    for (method, colour, label) in entries {
      svg.append(
        "<g transform=\"translate(\(x) \(top))\">"
          + shape(method, colour: colour) + "</g>")
      svg.append(SVGText.text(label, x: x + 9, y: top + 4, anchor: "start"))
      x += 9 + Double(label.count) * 6.2 + 16
    }
    let second = top + 22
    svg.append(
      "<circle cx=\"44\" cy=\"\(second)\" r=\"7.5\" fill=\"none\" "
        + "stroke=\"#444444\"/>")
    svg.append(
      SVGText.text(
        "some pixels hit in one and missed in the other", x: 58,
        y: second + 4, anchor: "start"))
    svg.append(
      "<line x1=\"330\" y1=\"\(second)\" x2=\"360\" y2=\"\(second)\" "
        + "stroke=\"#444444\" stroke-opacity=\"0.5\"/>")
    svg.append(
      SVGText.text(
        "one scene: naive to stable", x: 366, y: second + 4,
        anchor: "start"))
    svg.append(
      SVGText.text(
        "t_ref: the same rays in higher precision; 0: exact on every pixel",
        x: 40, y: second + 24, anchor: "start", size: 11))
    return svg
  }
}
