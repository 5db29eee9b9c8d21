import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

extension ImageComparison {
  /// What `raytrace compare` prints: the share within the tolerance and
  /// whether it meets `need`, the largest difference and where, and the
  /// pattern, in a few lines.
  package func report(_ nameA: String, _ nameB: String, need: Double)
    -> [String]
  {
    let kind =
      isEightBit
      ? "8-bit" : "raw values, \(channels) channel\(channels == 1 ? "" : "s")"
    var lines = ["\(nameA) and \(nameB): \(width)×\(height), \(kind)"]
    let unit =
      isEightBit
      ? "\(Self.number(tolerance)) level\(tolerance == 1 ? "" : "s")"
      : "\(Self.number(tolerance)) relative"
    lines.append(
      "within \(unit): \(Self.percent(share)) of pixels (\(differingPixels) "
        + "differ); needs \(Self.percent(need)): "
        + (share >= need ? "pass" : "FAIL"))
    if let largest {
      let name = channels == 3 ? ["red", "green", "blue"][largest.channel] : ""
      let size =
        isEightBit
        ? "\(Self.number(largest.difference)) levels"
        : "\(Self.number(largest.difference)) relative"
      lines.append(
        "largest difference: \(size) at column \(largest.column), row "
          + "\(largest.row)\(name.isEmpty ? "" : ", \(name)"): "
          + "\(Self.number(largest.a)) in \(nameA), \(Self.number(largest.b)) "
          + "in \(nameB)")
    }
    lines.append("pattern: " + describe(pattern, nameA, nameB))
    return lines
  }

  /// The pattern in words.
  func describe(_ pattern: Pattern, _ nameA: String, _ nameB: String)
    -> String
  {
    func moved(_ count: Int, _ positive: String, _ negative: String) -> String {
      let pixels = abs(count) == 1 ? "one pixel" : "\(abs(count)) pixels"
      return "\(pixels) \(count > 0 ? positive : negative)"
    }
    switch pattern {
    case .identical: return "identical"
    case .withinTolerance: return "the same within the tolerance"
    case .shifted(let x, let y):
      let parts =
        (x == 0 ? [] : [moved(x, "right", "left")])
        + (y == 0 ? [] : [moved(y, "down", "up")])
      return "\(nameB) is \(nameA) moved \(parts.joined(separator: " and ")) "
        + "(a pixel's position off by one: check where the pixel's centre is)"
    case .flippedRows:
      return "\(nameB) is \(nameA) upside down (rows in the opposite order: "
        + "row 0 is the top)"
    case .flippedColumns:
      return "\(nameB) is \(nameA) mirrored left to right"
    case .swappedChannels(let order):
      let names = ["red", "green", "blue"]
      return "\(nameB) is \(nameA) with its channels swapped ("
        + order.enumerated().map {
          "\(names[$0.offset]) holds \(names[$0.element])"
        }.joined(separator: ", ") + ")"
    case .normalConvention(let aIsAbsolute):
      let (absolute, shifted) = aIsAbsolute ? (nameA, nameB) : (nameB, nameA)
      return "the same normals in two conventions: \(absolute) shows |n| "
        + "(--style course), \(shifted) (n + 1)/2 (--style mit)"
    case .offset(let offsets):
      return "\(nameB) is \(nameA) plus a constant ("
        + offsets.map(Self.number).joined(separator: ", ")
        + (channels == 3 ? " in red, green, blue" : "") + ")"
    case .silhouettes(let share):
      return "on silhouettes: \(Self.percent(share)) of the differing pixels "
        + "are at an object's edge (a grazing ray, hit by one and missed by "
        + "the other)"
    case .region(let columns, let rows):
      return "in one region: columns \(columns.lowerBound)–"
        + "\(columns.upperBound), rows \(rows.lowerBound)–\(rows.upperBound)"
    case .everywhere:
      return "everywhere: no shift, flip, swap, convention or constant "
        + "explains them"
    }
  }

  static func percent(_ share: Double) -> String {
    let value = (share * 100_000).rounded(.down) / 1000
    return "\(number(value)) %"
  }

  /// A number briefly: integers without a fraction, others as the
  /// shortest Float that rounds to them (about 7 significant digits).
  static func number(_ value: Double) -> String {
    guard value.isFinite else { return "\(value)" }
    if value == value.rounded(), abs(value) < 1e15 { return "\(Int(value))" }
    return "\(Float(value))"
  }

  /// A picture of the differences: A's brightness dimmed to a third, and
  /// each differing pixel in heat (dark red for a difference at the
  /// tolerance, yellow for the largest).
  package func differenceImage(_ a: ReadImage, _ b: ReadImage) -> Image8 {
    let matcher = Matcher(eightBit: isEightBit, tolerance: tolerance)
    var largestFinite = 0.0
    for value in a.values where value.isFinite {
      largestFinite = max(largestFinite, abs(value))
    }
    let scale = isEightBit ? 1 : (largestFinite > 0 ? 255 / largestFinite : 0)
    let top = max(largest?.difference ?? 0, tolerance)
    var bytes = [UInt8](repeating: 0, count: width * height * 3)
    for row in 0..<height {
      for column in 0..<width {
        var brightness = 0.0
        var worst = 0.0
        for channel in 0..<channels {
          let (x, y) = (a[column, row, channel], b[column, row, channel])
          brightness += x.isFinite ? abs(x) * scale : 255
          worst = max(worst, matcher.difference(x, y))
        }
        let index = 3 * (row * width + column)
        if worst > tolerance {
          let heat = worst.isFinite ? min(1, worst / top) : 1
          bytes[index] = 255
          bytes[index + 1] = UInt8(min(255, 40 + 215 * heat))
          bytes[index + 2] = 0
        } else {
          let gray = UInt8(min(255, brightness / Double(channels) / 3))
          bytes[index] = gray
          bytes[index + 1] = gray
          bytes[index + 2] = gray
        }
      }
    }
    return Image8(width: width, height: height, bytes: bytes)
  }
}
