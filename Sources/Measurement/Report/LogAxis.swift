import RealModule

/// A logarithmic axis of a plot: values mapped linearly in log10 onto a
/// span of pixels.
package struct LogAxis: Sendable, Equatable {
  /// The log10 of the least and greatest values shown: 10^lowest …
  /// 10^highest.
  package var lowest: Double
  package var highest: Double
  /// The pixels of 10^lowest and 10^highest (for a vertical axis the
  /// first is the larger: SVG's y grows downwards).
  package var start: Double
  package var end: Double

  package init(
    lowest: Double, highest: Double, start: Double, end: Double
  ) {
    precondition(lowest < highest)
    self.lowest = lowest
    self.highest = highest
    self.start = start
    self.end = end
  }

  /// The decades around the positive finite `values`, at least one, with
  /// a margin of `margin` decades each side; (−1, 0) when there are none.
  package static func decades(
    around values: [Double], margin: Double = 0.15
  ) -> (lowest: Double, highest: Double) {
    let logs = values.filter { $0 > 0 && $0.isFinite }.map(log10)
    guard let low = logs.min(), let high = logs.max() else { return (-1, 0) }
    let lowest = (low - margin).rounded(.down)
    let highest = (high + margin).rounded(.up)
    return (lowest, Swift.max(highest, lowest + 1))
  }

  /// The pixel of the positive `value`.
  package func pixel(_ value: Double) -> Double {
    pixel(decade: log10(value))
  }

  /// The pixel of 10^`decade`, for a fractional decade too.
  package func pixel(decade: Double) -> Double {
    let fraction = (decade - lowest) / (highest - lowest)
    return start + (end - start) * fraction
  }

  /// The value at `pixel`: the inverse of `pixel(_:)`.
  package func value(atPixel pixel: Double) -> Double {
    let fraction = (pixel - start) / (end - start)
    return pow10(lowest + fraction * (highest - lowest))
  }

  /// The whole decades the axis spans, where its ticks go.
  package var decades: ClosedRange<Int> {
    Int(lowest.rounded(.up))...Swift.max(
      Int(lowest.rounded(.up)), Int(highest.rounded(.down)))
  }

  /// The axis as the SVG states it on its panel (`data-x-axis`,
  /// `data-y-axis`): "lowest highest start end".
  package var attribute: String {
    "\(lowest) \(highest) \(start) \(end)"
  }

  /// The axis `attribute` wrote.
  package init?(attribute: String) {
    let parts = attribute.split(separator: " ")
    guard parts.count == 4, let lowest = Double(parts[0]),
      let highest = Double(parts[1]), lowest < highest,
      let start = Double(parts[2]), let end = Double(parts[3])
    else { return nil }
    self.init(lowest: lowest, highest: highest, start: start, end: end)
  }
}

/// log10 and 10^x by the natural logarithm: the C library's spellings
/// differ by platform, and the plot needs neither's last ulp.
func log10(_ x: Double) -> Double { Double.log(x) / Double.log(10) }
func pow10(_ x: Double) -> Double { Double.exp(x * Double.log(10)) }
