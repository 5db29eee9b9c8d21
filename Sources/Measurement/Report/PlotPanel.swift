/// One panel of the report's plot: a frame with two logarithmic axes, a
/// grid at whole decades, tick labels, axis labels and a title, and the
/// pixel of a point in it.
///
/// A value of 0 has no place on a log scale: where the data hold one, the
/// panel draws a line below the lowest decade labelled "0", and points of
/// value 0 sit on it (`zeroY`).
struct PlotPanel {
  var x: LogAxis
  var y: LogAxis
  /// The pixel row of the "0" line, where a value is exactly 0.
  var zeroY: Double?
  var left: Double
  var right: Double
  var top: Double
  var bottom: Double

  /// A panel whose plotting area is (left, top) to (right, bottom), its
  /// axes spanning the decades around `xs` and `ys`.
  init(
    left: Double, right: Double, top: Double, bottom: Double,
    x: (lowest: Double, highest: Double), ys: [Double]
  ) {
    self.left = left
    self.right = right
    self.top = top
    self.bottom = bottom
    let hasZero = ys.contains(0)
    zeroY = hasZero ? bottom : nil
    let (lowest, highest) = LogAxis.decades(around: ys)
    self.x = LogAxis(
      lowest: x.lowest, highest: x.highest, start: left, end: right)
    // With a 0 line, the decades stop 24 pixels above it.
    self.y = LogAxis(
      lowest: lowest, highest: highest, start: hasZero ? bottom - 24 : bottom,
      end: top)
  }

  /// The pixel of (x, y): y = 0 on the "0" line.
  func point(_ x: Double, _ y: Double) -> (x: Double, y: Double) {
    (self.x.pixel(x), y == 0 ? (zeroY ?? bottom) : self.y.pixel(y))
  }

  /// The frame, grid, ticks and labels, opening the panel's group (with
  /// its axes as data attributes); `close` ends it.
  func open(
    name: String, title: String, xLabel: String, yLabel: String,
    xTicks: [(value: Double, label: String?)]? = nil
  ) -> [String] {
    var svg: [String] = []
    let zero = zeroY.map { " data-zero-y=\"\($0)\"" } ?? ""
    svg.append(
      "<g class=\"panel\" data-panel=\"\(name)\" "
        + "data-x-axis=\"\(x.attribute)\" data-y-axis=\"\(y.attribute)\""
        + "\(zero)>")
    let n = SVGText.number
    svg.append(
      "<rect x=\"\(n(left))\" y=\"\(n(top))\" width=\"\(n(right - left))\" "
        + "height=\"\(n(bottom - top))\" fill=\"#ffffff\" stroke=\"#444444\"/>"
    )
    // Vertical grid lines and the x ticks' labels.
    let ticks =
      xTicks ?? x.decades.map { (value: pow10(Double($0)), label: nil) }
    for tick in ticks {
      let px = x.pixel(tick.value)
      svg.append(line(px, top, px, bottom, colour: "#e4e4e4"))
      if let label = tick.label {
        svg.append(SVGText.text(label, x: px, y: bottom + 16, size: 11))
      } else {
        svg.append(
          SVGText.powerOfTen(
            Int(log10(tick.value).rounded()), x: px, y: bottom + 16))
      }
    }
    // Horizontal grid lines at every decade, labelled at most 14 times.
    let step = (y.decades.count + 13) / 14
    for decade in y.decades {
      let py = y.pixel(decade: Double(decade))
      svg.append(line(left, py, right, py, colour: "#e4e4e4"))
      if decade % step == 0 {
        svg.append(SVGText.powerOfTen(decade, x: left - 18, y: py + 4))
      }
    }
    if let zeroY {
      svg.append(line(left, zeroY, right, zeroY, colour: "#999999"))
      svg.append(
        SVGText.text("0", x: left - 8, y: zeroY + 4, anchor: "end", size: 11))
    }
    svg.append(
      SVGText.text(
        title, x: (left + right) / 2, y: top - 14, size: 14,
        extra: " font-weight=\"bold\""))
    svg.append(SVGText.text(xLabel, x: (left + right) / 2, y: bottom + 38))
    svg.append(
      SVGText.text(
        yLabel, x: left - 52, y: (top + bottom) / 2, rotate: -90))
    return svg
  }

  func close() -> String { "</g>" }

  func line(
    _ x1: Double, _ y1: Double, _ x2: Double, _ y2: Double, colour: String,
    width: Double = 1, dash: String? = nil, opacity: Double = 1
  ) -> String {
    let n = SVGText.number
    let dashing = dash.map { " stroke-dasharray=\"\($0)\"" } ?? ""
    let fading = opacity < 1 ? " stroke-opacity=\"\(n(opacity))\"" : ""
    return "<line x1=\"\(n(x1))\" y1=\"\(n(y1))\" x2=\"\(n(x2))\" "
      + "y2=\"\(n(y2))\" stroke=\"\(colour)\" stroke-width=\"\(n(width))\""
      + "\(dashing)\(fading)/>"
  }
}
