/// Which of the two conventions measured from the course's images (see
/// docs/CONVENTIONS.md): where pixels sample the screen, and how depth,
/// normals and colour become 8-bit values.
public enum ImageStyle: String, CaseIterable, Sendable {
  /// The Swift course: its own pixel mapping (columns at pixel centres,
  /// rows one pixel above them), depth range from the image, |n|,
  /// truncation.
  case course
  /// The original assignment: pixel corners, depth range from the command
  /// line, (n + 1)/2, rounding, point lights attenuated by falloff·dist².
  case mit

  /// The screen coordinate of column i of W, in [−1, 1], left to right.
  @inlinable
  public func screenX<S: RayScalar>(column i: Int, width: Int) -> S {
    switch self {
    case .course:
      return S(2 * i + 1) / S(width) - 1
    case .mit:
      return width > 1 ? S(2 * i) / S(width - 1) - 1 : 0
    }
  }

  /// The screen coordinate of row j of H, top to bottom.
  ///
  /// Course: 1 − (2j − 1)/H, one pixel above the pixel's centre. The
  /// course's code computes y = (H/2 − j)/(H/2) + 1/H, adding the half
  /// pixel that centres x with the sign that centres nothing for y, and
  /// every image it published carries that shift (docs/CONVENTIONS.md), so
  /// row 0 looks at y = 1 + 1/H and the bottom row at −1 + 3/H.
  @inlinable
  public func screenY<S: RayScalar>(row j: Int, height: Int) -> S {
    switch self {
    case .course:
      return 1 - S(2 * j - 1) / S(height)
    case .mit:
      return height > 1 ? 1 - S(2 * j) / S(height - 1) : 0
    }
  }

  /// The fractional column whose screen x is `x`: `screenX` inverted.
  public func column(screenX x: Double, width: Int) -> Double {
    switch self {
    case .course: return ((x + 1) * Double(width) - 1) / 2
    case .mit: return width > 1 ? (x + 1) * Double(width - 1) / 2 : 0
    }
  }

  /// The fractional row whose screen y is `y`: `screenY` inverted.
  public func row(screenY y: Double, height: Int) -> Double {
    switch self {
    case .course: return ((1 - y) * Double(height) + 1) / 2
    case .mit: return height > 1 ? (1 - y) * Double(height - 1) / 2 : 0
    }
  }
}
