import RealModule
import SceneIO
import Geometry

/// Per-pixel error in false colour, with a legend, for `raytrace report
/// --heatmaps`.
///
/// Colour is log10 of the relative error of t in units of the render's ε:
/// ≤ 1 ε dark blue, through green and yellow, to ≥ 10^8 ε white-hot red.
/// Pixels where both missed are black; where one hit and the other missed,
/// magenta. Below the image a 40-pixel strip shows the scale with a tick and
/// the exponent (0 to 8) at each decade, and says so in two lines: the
/// quantity and its unit (ε = 2^-23 or 2^-52), and the two other colours.
package enum ErrorHeatmap {
  package static let decades = 8
  static let legendHeight = 40
  static let magenta: (UInt8, UInt8, UInt8) = (255, 0, 255)

  package static func image(
    _ measurement: AccuracyMeasurement, width: Int, height: Int, epsilon: Double
  ) -> Image8 {
    let totalHeight = height + legendHeight
    var bytes = [UInt8](repeating: 0, count: width * totalHeight * 3)
    func put(_ column: Int, _ row: Int, _ colour: (UInt8, UInt8, UInt8)) {
      let index = 3 * (row * width + column)
      bytes[index] = colour.0
      bytes[index + 1] = colour.1
      bytes[index + 2] = colour.2
    }
    for row in 0..<height {
      for column in 0..<width {
        let error = measurement.perPixel[row * width + column]
        if error.isNaN { continue }
        if error.isInfinite {
          put(column, row, magenta)
          continue
        }
        put(column, row, colour(forUlps: error / epsilon))
      }
    }
    // The colour bar, 10 pixels high, then ticks and digits.
    for column in 0..<width {
      let fraction = Double(column) / Double(Swift.max(width - 1, 1))
      let ulps = Double.pow(10, fraction * Double(decades))
      for row in (height + 2)..<(height + 12) {
        put(column, row, colour(forUlps: ulps))
      }
    }
    let white: (UInt8, UInt8, UInt8) = (255, 255, 255)
    for decade in 0...decades {
      let column = Swift.min(width - 1, decade * (width - 1) / decades)
      for row in (height + 12)..<(height + 15) {
        put(column, row, white)
      }
      let left = Swift.min(Swift.max(column - 1, 0), width - 3)
      PixelFont.draw(
        "\(decade)", atColumn: left, row: height + 16, limit: width
      ) { put($0, $1, white) }
    }
    let exponent = epsilon.exponent  // ε is a power of two
    let lines = [
      "colour: log10 of |t-t_ref|/t_ref in units of eps=2^\(exponent)",
      "black: both missed, magenta: one hit, one missed",
    ]
    for (index, line) in lines.enumerated() {
      PixelFont.draw(
        line, atColumn: 1, row: height + 25 + 8 * index, limit: width
      ) { put($0, $1, white) }
    }
    return Image8(width: width, height: totalHeight, bytes: bytes)
  }

  /// A perceptually ordered ramp (dark blue, cyan, green, yellow, red,
  /// white) over 0 to `decades` decades of ulps.
  static func colour(forUlps ulps: Double) -> (UInt8, UInt8, UInt8) {
    let stops: [(Double, Double, Double)] = [
      (0.05, 0.05, 0.35), (0.0, 0.55, 0.85), (0.1, 0.75, 0.3),
      (0.95, 0.85, 0.1), (0.9, 0.15, 0.1), (1, 1, 1),
    ]
    let position = ulps > 1 ? log10(ulps) : 0
    let scaled =
      Swift.min(Swift.max(position / Double(decades), 0), 1)
      * Double(stops.count - 1)
    let index = Swift.min(Int(scaled), stops.count - 2)
    let f = scaled - Double(index)
    let a = stops[index]
    let b = stops[index + 1]
    func channel(_ x: Double, _ y: Double) -> UInt8 {
      UInt8((x + (y - x) * f) * 255)
    }
    return (channel(a.0, b.0), channel(a.1, b.1), channel(a.2, b.2))
  }
}
