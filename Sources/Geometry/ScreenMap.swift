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

  /// Screen x of the centre of pixel column `column`.
  @inlinable
  public func x<S: RayScalar>(column: Int) -> S {
    style.screenX(column: column, width: width)
  }

  /// Screen y of the centre of pixel row `row` (row 0 at the top).
  @inlinable
  public func y<S: RayScalar>(row: Int) -> S {
    style.screenY(row: row, height: height)
  }

  /// The (fractional) column whose centre is at screen x: the inverse of
  /// `x(column:)`.
  public func column(x: Double) -> Double {
    style.column(screenX: x, width: width)
  }

  /// The (fractional) row whose centre is at screen y: the inverse of
  /// `y(row:)`.
  public func row(y: Double) -> Double {
    style.row(screenY: y, height: height)
  }
}

/// How an engine turns a normal or a colour into an 8-bit pixel, for an
/// output written only as an 8-bit image: its style's rule
/// (`RenderSettings.quantization`).
public struct Quantization: Sendable {
  @usableFromInline let style: ImageStyle

  @inlinable
  public init(style: ImageStyle) { self.style = style }

  /// A normal's pixel: |n| per component (course) or (n + 1)/2 (mit).
  @inlinable @inline(__always)
  public func pixel<S: RayScalar>(normal: Vector3<S>) -> (UInt8, UInt8, UInt8)
  {
    style.pixel(normal: normal)
  }

  /// A colour's pixel, each component quantised.
  @inlinable @inline(__always)
  public func pixel<S: RayScalar>(_ value: Vector3<S>) -> (UInt8, UInt8, UInt8)
  {
    style.pixel(value)
  }
}
