/// The pieces of SVG text the report's plot writes: numbers of pixels,
/// escaped text, elements.
enum SVGText {
  /// `value` with two decimals (a hundredth of a pixel), without the
  /// C library's formatting.
  static func number(_ value: Double) -> String {
    guard value.isFinite else { return "0" }
    let hundredths = Int((value * 100).rounded())
    let sign = hundredths < 0 ? "-" : ""
    let whole = abs(hundredths) / 100
    let fraction = abs(hundredths) % 100
    return "\(sign)\(whole)." + (fraction < 10 ? "0" : "") + "\(fraction)"
  }

  /// `text` with XML's five special characters escaped, for text and
  /// attribute values alike.
  static func escaped(_ text: String) -> String {
    var result = ""
    for character in text {
      switch character {
      case "&": result += "&amp;"
      case "<": result += "&lt;"
      case ">": result += "&gt;"
      case "\"": result += "&quot;"
      case "'": result += "&apos;"
      default: result.append(character)
      }
    }
    return result
  }

  /// A text element at (x, y); `anchor` is start, middle or end, `rotate`
  /// turns it about its point (−90 for a vertical axis's label).
  static func text(
    _ content: String, x: Double, y: Double, anchor: String = "middle",
    size: Int = 12, rotate: Int = 0, extra: String = ""
  ) -> String {
    let turn =
      rotate == 0
      ? "" : " transform=\"rotate(\(rotate) \(number(x)) \(number(y)))\""
    return "<text x=\"\(number(x))\" y=\"\(number(y))\" "
      + "text-anchor=\"\(anchor)\" font-size=\"\(size)\"\(turn)\(extra)>"
      + "\(content)</text>"
  }

  /// 10 to the power `exponent` as the tick labels write it: 10 with a
  /// raised exponent.
  static func powerOfTen(_ exponent: Int, x: Double, y: Double) -> String {
    "<text x=\"\(number(x))\" y=\"\(number(y))\" text-anchor=\"middle\" "
      + "font-size=\"11\">10<tspan dy=\"-5\" font-size=\"8\">\(exponent)"
      + "</tspan></text>"
  }
}
