/// An image mapped onto a surface by texture coordinates, looked up as the
/// course's loader does: the nearest texel, no filtering, no wrapping.
public struct Texture: Hashable, Sendable {
  public let image: Image8

  public init(image: Image8) {
    self.image = image
  }

  /// The texel at (u, v) as a colour in [0, 1]: column min(⌊u·W⌋, W − 1)
  /// and row min(⌊(1 − v)·H⌋, H − 1) from the image's top, so u = 0 is
  /// the left edge, v = 0 the bottom and u = 1 or v = 1 the last texel.
  /// Coordinates outside [0, 1] (or NaN) take the nearest edge's texel.
  @inlinable
  public func color<S: RayScalar>(at coordinate: TextureCoordinate<S>) -> RGB<S>
  {
    let column = Self.index(coordinate.u, count: image.width)
    let row = Self.index(1 - coordinate.v, count: image.height)
    let (r, g, b) = image[column, row]
    return Vector3(S(r), S(g), S(b)) / 255
  }

  /// ⌊x·count⌋ clamped to 0…count − 1; NaN gives 0.
  @inlinable
  static func index<S: RayScalar>(_ x: S, count: Int) -> Int {
    let scaled = (x * S(count)).rounded(.down)
    guard scaled > 0 else { return 0 }
    guard scaled < S(count - 1) else { return count - 1 }
    return Int(scaled)
  }
}

/// A point (u, v) of a texture: u = 0 its left edge, v = 0 its bottom.
public struct TextureCoordinate<Scalar: RayScalar>: Hashable, Sendable {
  public var u: Scalar
  public var v: Scalar

  @inlinable
  public init(_ u: Scalar, _ v: Scalar) {
    self.u = u
    self.v = v
  }

  @inlinable
  public init<Other: RayScalar>(_ other: TextureCoordinate<Other>) {
    self.init(Scalar(other.u), Scalar(other.v))
  }
}
