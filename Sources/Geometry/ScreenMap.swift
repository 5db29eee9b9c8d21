/// Where each pixel's centre falls on the screen [−1, 1]², and back, for
/// one image: its style's map at its size (docs/CONVENTIONS.md). The
/// engines build their rays through it (`RenderSettings.screen`) without
/// asking which style it is.
public struct ScreenMap: Sendable {
  @usableFromInline let style: ImageStyle
  public let width: Int
  public let height: Int

  @inlinable
  public init(style: ImageStyle, width: Int, height: Int) {
    self.style = style
    self.width = width
    self.height = height
  }

  /// Screen x of column i's centre, in [−1, 1], left to right: the
  /// course's pixel centres, the mit style's pixel corners.
  @inlinable
  public func x<S: RayScalar>(column i: Int) -> S {
    switch style {
    case .course: S(2 * i + 1) / S(width) - 1
    case .mit: width > 1 ? S(2 * i) / S(width - 1) - 1 : 0
    }
  }

  /// Screen y of row j, top to bottom. Course: 1 − (2j − 1)/H, one pixel
  /// above the pixel's centre. The course's code computes
  /// y = (H/2 − j)/(H/2) + 1/H, adding the half pixel that centres x with
  /// the sign that centres nothing for y, and every image it published
  /// carries that shift (docs/CONVENTIONS.md): row 0 looks at y = 1 + 1/H
  /// and the bottom row at −1 + 3/H.
  @inlinable
  public func y<S: RayScalar>(row j: Int) -> S {
    switch style {
    case .course: 1 - S(2 * j - 1) / S(height)
    case .mit: height > 1 ? 1 - S(2 * j) / S(height - 1) : 0
    }
  }

  /// The fractional column whose screen x is `x`: `x(column:)` inverted.
  public func column(x: Double) -> Double {
    switch style {
    case .course: ((x + 1) * Double(width) - 1) / 2
    case .mit: width > 1 ? (x + 1) * Double(width - 1) / 2 : 0
    }
  }

  /// The fractional row whose screen y is `y`: `y(row:)` inverted.
  public func row(y: Double) -> Double {
    switch style {
    case .course: ((1 - y) * Double(height) + 1) / 2
    case .mit: height > 1 ? (1 - y) * Double(height - 1) / 2 : 0
    }
  }
}
