import RealModule

/// A pinhole camera with a horizontal field of view (the course's
/// `PerspectiveCamera`).
///
/// The basis is w = direction, u = w × up, v = u × w (all unit length): u
/// points right and v up in the image. A screen point (x, y) in [−1, 1]²
/// maps to the ray direction x·u + (H/W)·y·v + D·w with
/// D = 1 / tan(angle / 2), normalised, so that t is a distance.
public struct PerspectiveCamera<Scalar: RayScalar>: Hashable, Sendable {
  public var center: Vector3<Scalar>
  public var direction: Vector3<Scalar>
  public var horizontal: Vector3<Scalar>
  /// The image's vertical axis, u × w: `up` made perpendicular to the view.
  public var up: Vector3<Scalar>
  /// The scene's `up`, normalised but not made perpendicular: the original
  /// assignment's images use it as the image's vertical axis (see
  /// `styled(_:)`).
  public var givenUp: Vector3<Scalar>
  /// Horizontal field of view in degrees, 0 < angle < 180.
  public var angle: Scalar
  /// D = 1 / tan(angle / 2): the image plane's distance for a half-width of 1.
  public var focalDistance: Scalar

  /// Nil when the direction is zero or parallel to up, or the angle is not
  /// in (0, 180): there is no camera basis then.
  public init?(
    center: Vector3<Scalar>, direction: Vector3<Scalar>,
    up: Vector3<Scalar>, angle: Scalar
  ) {
    guard angle > 0 && angle < 180, direction.maxMagnitude > 0 else {
      return nil
    }
    let w = direction.normalized()
    let right = w.cross(up.normalized())
    guard right.maxMagnitude > 0, right.isFinite else { return nil }
    let u = right.normalized()
    self.center = center
    self.direction = w
    self.horizontal = u
    self.up = u.cross(w)
    self.givenUp = up.normalized()
    self.angle = angle
    self.focalDistance = 1 / Scalar.tan(angle * .pi / 360)
    guard focalDistance.isFinite && focalDistance > 0 else { return nil }
  }

  /// The same camera in another precision, each vector rounded once from
  /// the basis computed here (so Float renders get Double's basis, rounded).
  public init<Other: RayScalar>(_ other: PerspectiveCamera<Other>) {
    center = Vector3(other.center)
    direction = Vector3(other.direction)
    horizontal = Vector3(other.horizontal)
    up = Vector3(other.up)
    givenUp = Vector3(other.givenUp)
    angle = Scalar(other.angle)
    focalDistance = Scalar(other.focalDistance)
  }

  /// The unit direction through screen point (x, y); `aspect` is H / W.
  @inlinable
  @_specialize(where Scalar == Double)
  public func rayDirection(x: Scalar, y: Scalar, aspect: Scalar) -> Vector3<
    Scalar
  > {
    rayDirection(x: x, rowBase: rowBase(y: y, aspect: aspect))
  }

  /// The part of the ray direction shared by a row of pixels:
  /// (H/W)·y·v + D·w.
  @inlinable
  public func rowBase(y: Scalar, aspect: Scalar) -> Vector3<Scalar> {
    up * (aspect * y) + direction * focalDistance
  }

  /// The unit direction through screen x on the row of `rowBase`.
  @inlinable
  public func rayDirection(x: Scalar, rowBase: Vector3<Scalar>) -> Vector3<
    Scalar
  > {
    throughScreen(x: x, rowBase: rowBase).normalizedByReciprocal()
  }

  /// `rayDirection(x:rowBase:)` before it is normalised: x·u + rowBase.
  @inlinable
  public func throughScreen(x: Scalar, rowBase: Vector3<Scalar>) -> Vector3<
    Scalar
  > {
    horizontal * x + rowBase
  }
}
