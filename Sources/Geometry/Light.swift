/// A light of the course's scenes. No shadows are cast: the assignment is a
/// ray caster, not a ray tracer.
public enum Light<Scalar: RayScalar>: Hashable, Sendable {
  /// A point light. In the mit style its colour is divided by
  /// falloff·distance² when a falloff is given; the course style ignores it.
  case point(position: Vector3<Scalar>, color: RGB<Scalar>, falloff: Scalar?)
  /// Light travelling along `direction` (unit length) from infinitely far.
  case directional(direction: Vector3<Scalar>, color: RGB<Scalar>)

  /// The unit vector from `point` towards the light and the light's colour
  /// arriving there.
  @inlinable
  @_specialize(where Scalar == Double)
  public func illumination(
    at point: Vector3<Scalar>, attenuate: Bool
  ) -> (toLight: Vector3<Scalar>, color: RGB<Scalar>) {
    switch self {
    case .directional(let direction, let color):
      return (-direction, color)
    case .point(let position, let color, let falloff):
      let offset = position - point
      let toLight = offset.normalized()
      guard attenuate, let falloff else { return (toLight, color) }
      return (toLight, color / (falloff * offset.lengthSquared))
    }
  }

  public init<Other: RayScalar>(_ other: Light<Other>) {
    switch other {
    case .point(let position, let color, let falloff):
      self = .point(
        position: Vector3(position), color: Vector3(color),
        falloff: falloff.map { Scalar($0) })
    case .directional(let direction, let color):
      self = .directional(direction: Vector3(direction), color: Vector3(color))
    }
  }
}
