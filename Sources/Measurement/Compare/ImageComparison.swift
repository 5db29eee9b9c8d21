import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// Two images of the same size compared pixel by pixel, and what the
/// differences look like (`raytrace compare`, `raytrace SCENE --check`).
///
/// A pixel matches when every channel is within the tolerance: a number of
/// levels for 8-bit images, a relative bound |a − b| ≤ tol·max(|a|, |b|) for
/// raw values (two infinities of the same sign, or two NaNs, match).
package struct ImageComparison: Sendable {
  package let width: Int
  package let height: Int
  package let channels: Int
  package let isEightBit: Bool
  package let tolerance: Double
  /// Pixels that match, over all pixels.
  package let share: Double
  package let differingPixels: Int
  /// The largest difference of one channel (in levels, or relative for raw
  /// values), where it is, and both values; nil when nothing differs.
  package let largest: Largest?
  /// The first differing pixel in row order (row, then column), or nil.
  package let first: (column: Int, row: Int)?
  /// What the differences look like, in a few words.
  package let pattern: Pattern

  package struct Largest: Sendable {
    package var difference: Double
    package var column: Int
    package var row: Int
    package var channel: Int
    package var a: Double
    package var b: Double
  }

  /// The shapes a difference takes: the mistakes a student makes, then
  /// where the differing pixels lie.
  package enum Pattern: Sendable, Equatable {
    /// No channel differs at all.
    case identical
    /// Every pixel within the tolerance, some not exactly equal.
    case withinTolerance
    /// B is A moved by whole pixels (x right, y down): it matches after
    /// moving it back.
    case shifted(x: Int, y: Int)
    /// B's rows are A's in the opposite order.
    case flippedRows
    /// B's columns are A's in the opposite order.
    case flippedColumns
    /// B's channels are A's in another order (B's channel i is A's
    /// `order[i]`).
    case swappedChannels(order: [Int])
    /// One image holds normals as |n| (the course style), the other as
    /// (n + 1)/2 (the mit style): they match once converted.
    case normalConvention(aIsAbsolute: Bool)
    /// B is A plus a constant per channel.
    case offset([Double])
    /// The differing pixels lie along the edges of objects.
    case silhouettes(share: Double)
    /// The differing pixels lie in one rectangle.
    case region(columns: ClosedRange<Int>, rows: ClosedRange<Int>)
    /// The differing pixels are spread over the image.
    case everywhere
  }

  /// The default tolerance: 2 levels for 8-bit images (truncation against
  /// rounding, and one level of a renderer's own arithmetic), and 10⁻⁶
  /// relative for raw values (about 8 ε of Float, the precision PFM
  /// stores: a Double render written as PFM and a Float render differ by a
  /// few of its roundings).
  package static func defaultTolerance(eightBit: Bool) -> Double {
    eightBit ? 2 : 1e-6
  }

  /// Compares `a` and `b`, which must have the same size and channels.
  package init(_ a: ReadImage, _ b: ReadImage, tolerance: Double) {
    precondition(
      a.width == b.width && a.height == b.height && a.channels == b.channels)
    width = a.width
    height = a.height
    channels = a.channels
    isEightBit = a.isEightBit && b.isEightBit
    self.tolerance = tolerance
    let matcher = Matcher(eightBit: isEightBit, tolerance: tolerance)
    var differing = [Bool](repeating: false, count: width * height)
    var count = 0
    var exact = true
    var largest: Largest?
    var first: (column: Int, row: Int)?
    for row in 0..<height {
      for column in 0..<width {
        var differs = false
        for channel in 0..<channels {
          let (x, y) = (a[column, row, channel], b[column, row, channel])
          if x != y && !(x.isNaN && y.isNaN) { exact = false }
          let difference = matcher.difference(x, y)
          if difference > tolerance { differs = true }
          if difference > (largest?.difference ?? 0) {
            largest = Largest(
              difference: difference, column: column, row: row,
              channel: channel, a: x, b: y)
          }
        }
        if differs {
          differing[row * width + column] = true
          count += 1
          if first == nil { first = (column, row) }
        }
      }
    }
    differingPixels = count
    share = Double(width * height - count) / Double(width * height)
    self.largest = largest
    self.first = first
    if count == 0 {
      pattern = exact ? .identical : .withinTolerance
    } else {
      pattern = Self.pattern(
        a, b, differing: differing, count: count, matcher: matcher)
    }
  }

  /// How one channel's two values are measured against the tolerance.
  struct Matcher {
    var eightBit: Bool
    var tolerance: Double

    func difference(_ x: Double, _ y: Double) -> Double {
      if eightBit { return abs(x - y) }
      if x == y || (x.isNaN && y.isNaN) { return 0 }
      guard x.isFinite && y.isFinite else { return .infinity }
      return abs(x - y) / max(abs(x), abs(y))
    }

    func matches(_ x: Double, _ y: Double) -> Bool {
      difference(x, y) <= tolerance
    }
  }

  /// The share of pixels of A that match `b(column, row, channel)` where
  /// it is defined (nil outside the image, for shifts).
  static func share(
    _ a: ReadImage, matcher: Matcher,
    _ b: (Int, Int, Int) -> Double?
  ) -> Double {
    var compared = 0
    var matched = 0
    for row in 0..<a.height {
      pixels: for column in 0..<a.width {
        var all = true
        for channel in 0..<a.channels {
          guard let y = b(column, row, channel) else { continue pixels }
          if !matcher.matches(a[column, row, channel], y) { all = false }
        }
        compared += 1
        if all { matched += 1 }
      }
    }
    return compared == 0 ? 0 : Double(matched) / Double(compared)
  }

  /// The first explanation that accounts for nearly every pixel (99.9 %
  /// after the conversion) and for the difference itself (it leaves at
  /// most a tenth of the `count` differing pixels differing), else where
  /// the differing pixels lie. Without the second condition a grey image
  /// with one pixel off read as "channels swapped" (swapping changes
  /// nothing in grey) and a left-right symmetric one as "mirrored".
  static func pattern(
    _ a: ReadImage, _ b: ReadImage, differing: [Bool], count: Int,
    matcher: Matcher
  ) -> Pattern {
    let (width, height) = (a.width, a.height)
    let enough = 0.999
    let differingShare = Double(count) / Double(max(1, width * height))
    func explains(_ converted: (Int, Int, Int) -> Double?, loose: Bool = false)
      -> Bool
    {
      var looser = matcher
      if loose { looser.tolerance += matcher.eightBit ? 3 : 1e-3 }
      let matched = share(a, matcher: looser, converted)
      return matched >= enough && 1 - matched <= differingShare / 10
    }
    // Moved by a pixel or two: B(c, r) = A(c − x, r − y).
    for (x, y) in [(0, 1), (0, -1), (1, 0), (-1, 0), (1, 1), (-1, -1),
      (1, -1), (-1, 1), (0, 2), (0, -2), (2, 0), (-2, 0)]
    where width > 2 * abs(x) && height > 2 * abs(y) {
      if explains({ column, row, channel in
        let (c, r) = (column + x, row + y)
        guard c >= 0, r >= 0, c < width, r < height else { return nil }
        return b[c, r, channel]
      }) {
        return .shifted(x: x, y: y)
      }
    }
    if height > 1, explains({ b[$0, height - 1 - $1, $2] }) {
      return .flippedRows
    }
    if width > 1, explains({ b[width - 1 - $0, $1, $2] }) {
      return .flippedColumns
    }
    if a.channels == 3 {
      for order in [[0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]] {
        // B's channel i holds A's order[i]: A's channel j is B's at the
        // index where order names j.
        if explains({ column, row, channel in
          b[column, row, order.firstIndex(of: channel) ?? channel]
        }) {
          return .swappedChannels(order: order)
        }
      }
      if a.isEightBit && b.isEightBit {
        // |n|·255 against (n + 1)/2·255: each converted to the other's.
        let absolute = { (v: Double) in abs(2 * v / 255 - 1) * 255 }
        if explains({ absolute(b[$0, $1, $2]) }, loose: true) {
          return .normalConvention(aIsAbsolute: true)
        }
        let bAbsolute = ReadImage(
          width: width, height: height, channels: 3,
          values: a.values.map(absolute), isEightBit: true)
        let matched = share(bAbsolute, matcher: {
          var m = matcher
          m.tolerance += 3
          return m
        }(), { b[$0, $1, $2] })
        if matched >= enough && 1 - matched <= differingShare / 10 {
          return .normalConvention(aIsAbsolute: false)
        }
      }
    }
    // A constant per channel: the median difference, if it explains all.
    var offsets: [Double] = []
    for channel in 0..<a.channels {
      var differences: [Double] = []
      for index in stride(from: channel, to: a.values.count, by: a.channels)
      where a.values[index].isFinite && b.values[index].isFinite {
        differences.append(b.values[index] - a.values[index])
      }
      offsets.append(median(differences))
    }
    // Compared as A plus the offset (clamped to the 8-bit range where the
    // images are 8-bit, as a brighter image saturates) against B.
    if offsets.allSatisfy(\.isFinite), offsets.contains(where: { $0 != 0 }) {
      let shifted = ReadImage(
        width: width, height: height, channels: a.channels,
        values: a.values.enumerated().map { index, value in
          let moved = value + offsets[index % a.channels]
          return a.isEightBit ? min(255, max(0, moved)) : moved
        }, isEightBit: a.isEightBit)
      if share(shifted, matcher: matcher, { b[$0, $1, $2] }) >= enough {
        return .offset(offsets)
      }
    }
    return whereDiffering(a, b, differing: differing, count: count)
  }

  /// Silhouettes, one region, or everywhere.
  static func whereDiffering(
    _ a: ReadImage, _ b: ReadImage, differing: [Bool], count: Int
  ) -> Pattern {
    let (width, height) = (a.width, a.height)
    // An edge: a pixel that differs much from a 4-neighbour in A or in B
    // (a jump of a tenth of the range, or a hit beside a miss).
    func jump(_ image: ReadImage, _ p: (Int, Int), _ q: (Int, Int)) -> Bool {
      for channel in 0..<image.channels {
        let (x, y) = (image[p.0, p.1, channel], image[q.0, q.1, channel])
        if x.isFinite != y.isFinite { return true }
        let scale = image.isEightBit ? 255 : max(abs(x), abs(y), 1e-300)
        if abs(x - y) > 0.1 * scale { return true }
      }
      return false
    }
    func onEdge(_ image: ReadImage, _ column: Int, _ row: Int) -> Bool {
      for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
        let (c, r) = (column + dx, row + dy)
        guard c >= 0, r >= 0, c < width, r < height else { continue }
        if jump(image, (column, row), (c, r)) { return true }
      }
      return false
    }
    // A pixel at a silhouette is at an edge of both images (an object's
    // rim seen a pixel apart); noise in one image is at "edges" of that
    // image only.
    var edges = (a: 0, b: 0)
    var (lowColumn, highColumn, lowRow, highRow) = (width, -1, height, -1)
    for row in 0..<height {
      for column in 0..<width where differing[row * width + column] {
        if onEdge(a, column, row) { edges.a += 1 }
        if onEdge(b, column, row) { edges.b += 1 }
        lowColumn = min(lowColumn, column)
        highColumn = max(highColumn, column)
        lowRow = min(lowRow, row)
        highRow = max(highRow, row)
      }
    }
    guard highColumn >= lowColumn else { return .everywhere }
    let columns = lowColumn...highColumn
    let rows = lowRow...highRow
    let onEdges = Double(min(edges.a, edges.b)) / Double(count)
    if onEdges >= 0.8 { return .silhouettes(share: onEdges) }
    let box = columns.count * rows.count
    if box <= width * height / 4, Double(count) >= 0.3 * Double(box) {
      return .region(columns: columns, rows: rows)
    }
    return .everywhere
  }
}
