/// An axis-aligned box, in Double: the bound the course's mesh hierarchy
/// and the compiled engine's test of other shapes check before a shape.
public struct BoundingBox: Hashable, Sendable {
  public var lower: Vector3<Double>
  public var upper: Vector3<Double>

  @inlinable
  public init(lower: Vector3<Double>, upper: Vector3<Double>) {
    self.lower = lower
    self.upper = upper
  }

  /// The smallest box holding every point.
  @inlinable
  public init(around points: Vector3<Double>...) {
    self.init(lower: points[0], upper: points[0])
    for point in points.dropFirst() { formUnion(point) }
  }

  /// The smallest box holding both.
  @inlinable
  public func union(_ other: BoundingBox) -> BoundingBox {
    BoundingBox(
      lower: Vector3(
        min(lower.x, other.lower.x), min(lower.y, other.lower.y),
        min(lower.z, other.lower.z)),
      upper: Vector3(
        max(upper.x, other.upper.x), max(upper.y, other.upper.y),
        max(upper.z, other.upper.z)))
  }

  @inlinable
  public mutating func formUnion(_ point: Vector3<Double>) {
    self = union(BoundingBox(lower: point, upper: point))
  }

  @inlinable
  public var center: Vector3<Double> { (lower + upper) * 0.5 }

  /// The box of the eight corners moved by `matrix`.
  public func transformed(by matrix: Matrix4<Double>) -> BoundingBox {
    var box: BoundingBox?
    for corner in 0..<8 {
      let point = Vector3(
        corner & 1 == 0 ? lower.x : upper.x,
        corner & 2 == 0 ? lower.y : upper.y,
        corner & 4 == 0 ? lower.z : upper.z)
      let moved = matrix.transformPoint(point)
      box = box?.union(BoundingBox(lower: moved, upper: moved))
        ?? BoundingBox(lower: moved, upper: moved)
    }
    return box ?? self
  }

  /// Whether the ray meets the box between tMin and tMax (the slab test),
  /// given the reciprocals of its direction's components. Conservative: a
  /// ray that grazes a face counts as meeting it.
  @inlinable
  public func isHit(
    by ray: Ray<Double>, reciprocal: Vector3<Double>, after tMin: Double,
    before tMax: Double
  ) -> Bool {
    var near = tMin
    var far = tMax
    for axis in 0..<3 {
      let t0 = (lower[axis] - ray.origin[axis]) * reciprocal[axis]
      let t1 = (upper[axis] - ray.origin[axis]) * reciprocal[axis]
      // NaN (0 · ∞, a ray in the slab's plane) leaves the interval as is.
      let (enter, leave) = t0 <= t1 ? (t0, t1) : (t1, t0)
      if enter > near { near = enter }
      if leave < far { far = leave }
      // A few ulps of slack: t0 and t1 are rounded, and a hit on the
      // box's face must not be lost to that rounding.
      let slack = 4 * Double.ulpOfOne * Swift.max(near.magnitude, far.magnitude)
      if near > far + slack { return false }
    }
    return true
  }
}
