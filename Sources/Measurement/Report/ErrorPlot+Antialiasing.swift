/// The plot's second panel: antialiasing's error against samples per
/// pixel.
extension ErrorPlot {
  static func antialiasingPanel(_ rows: [AntialiasingRow], left: Double)
    -> [String]
  {
    let samples = rows.map { Double($0.samples) }
    let panel = PlotPanel(
      left: left + 80, right: left + antialiasingWidth - 24, top: 48,
      bottom: height - 130,
      x: (
        log10(samples.min() ?? 1) - 0.15, log10(samples.max() ?? 64) + 0.15
      ),
      ys: rows.map(\.measurement.rootMeanSquare))
    let counts = Array(Set(rows.map(\.samples))).sorted()
    var svg = panel.open(
      name: "antialiasing", title: "Antialiasing",
      xLabel: "samples per pixel (log scale)",
      yLabel: "RMS error of the shaded image, colour in [0, 1]",
      xTicks: counts.map { (Double($0), "\($0)") })
    let scenes = rows.map(\.scene).reduce(into: [String]()) {
      if !$0.contains($1) { $0.append($1) }
    }
    let n = SVGText.number
    // 1/√N through the scenes' mean one-sample error (geometric mean).
    let single = rows.filter { $0.samples == counts.first }
      .map(\.measurement.rootMeanSquare).filter { $0 > 0 }
    if let first = counts.first, let last = counts.last, first < last,
      !single.isEmpty
    {
      let anchor = pow10(single.map(log10).reduce(0, +) / Double(single.count))
      let a = panel.point(Double(first), anchor)
      let b = panel.point(
        Double(last), anchor * (Double(first) / Double(last)).squareRoot())
      svg.append(
        panel.line(
          a.x, a.y, b.x, b.y, colour: "#888888", width: 1.2, dash: "6 4"))
      svg.append(
        SVGText.text(
          "∝ 1/√N", x: b.x - 4, y: b.y - 8, anchor: "end", size: 11,
          extra: " fill=\"#666666\""))
    }
    for (index, scene) in scenes.enumerated() {
      let colour = sceneColours[index % sceneColours.count]
      let points = rows.filter { $0.scene == scene }.sorted {
        $0.samples < $1.samples
      }.map {
        (
          row: $0,
          at: panel.point(Double($0.samples), $0.measurement.rootMeanSquare)
        )
      }
      let path = points.map { "\(n($0.at.x)),\(n($0.at.y))" }
        .joined(separator: " ")
      svg.append(
        "<polyline points=\"\(path)\" fill=\"none\" stroke=\"\(colour)\" "
          + "stroke-width=\"1.2\"/>")
      for (row, at) in points {
        svg.append(
          "<g class=\"mark\" data-panel=\"antialiasing\" "
            + "data-scene=\"\(SVGText.escaped(scene))\" "
            + "data-x=\"\(row.samples)\" "
            + "data-y=\"\(row.measurement.rootMeanSquare)\" "
            + "transform=\"translate(\(n(at.x)) \(n(at.y)))\">"
            + "<title>\(SVGText.escaped(scene)), \(row.samples) samples: "
            + "RMS \(row.measurement.rootMeanSquare)</title>"
            + "<circle r=\"3.5\" fill=\"\(colour)\"/></g>")
      }
      // The key: one line per scene below the panel.
      // The key: four scenes a column below the panel.
      let y = height - 72 + 16 * Double(index % 4)
      let x = left + 40 + 190 * Double(index / 4)
      svg.append(panel.line(x, y, x + 24, y, colour: colour, width: 1.5))
      svg.append(
        SVGText.text(
          SVGText.escaped(scene), x: x + 30, y: y + 4, anchor: "start"))
    }
    svg.append(panel.close())
    return svg
  }
}
