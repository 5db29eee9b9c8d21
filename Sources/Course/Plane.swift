import Geometry

/// A plane: the points P with n·P = d (the text format's `normal` and
/// `offset`).
public struct Plane: Hittable {
  /// Unit length.
  public var normal: Vector3<Double>
  public var offset: Double
  public var materialIndex: Int

  public init(normal: Vector3<Double>, offset: Double, materialIndex: Int = 0) {
    self.normal = normal
    self.offset = offset
    self.materialIndex = materialIndex
  }

  /// The hit in (tMin, tMax), or nil: n·(o + t·d) = d gives
  /// t = (d − n·o) / (n·d). A ray parallel to the plane (n·d = 0) gives an
  /// infinite or undefined t, which no interval holds. The normal is the
  /// plane's own, whichever side the ray comes from.
  public func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    // BEGIN SOLUTION week 1: camera and planes — the t where n·(o + t·d) = d
    //   if it lies in (tMin, tMax), with the plane's own normal
    let t = (offset - normal.dot(ray.origin)) / normal.dot(ray.direction)
    guard tMin < t && t < tMax else { return nil }
    return Hit(t: t, normal: normal, materialIndex: materialIndex)
    // END SOLUTION
  }

  /// A plane has no bound.
  public var boundingBox: BoundingBox? { nil }
}
