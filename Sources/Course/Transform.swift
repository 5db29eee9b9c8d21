import Geometry

/// An object placed by a matrix M (the course's `Transform`): the object's
/// points P appear at M·P.
public struct Transform: Hittable {
  public var matrix: Matrix4<Double>
  /// M⁻¹, computed once.
  public var inverse: Matrix4<Double>
  public var object: any Hittable

  /// Nil when M has no inverse (a scale of zero).
  public init?(matrix: Matrix4<Double>, object: any Hittable) {
    guard let inverse = matrix.inverse() else { return nil }
    self.matrix = matrix
    self.inverse = inverse
    self.object = object
  }

  /// The object's hit, found in the object's own space (lecture 5): the
  /// ray is taken there by M⁻¹ (its direction not normalised, so t names
  /// the same point in both spaces), and the normal brought back by the
  /// inverse transpose (M⁻¹)ᵀ, which keeps it perpendicular to the moved
  /// surface, then normalised.
  public func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    // BEGIN SOLUTION week 4: transforms — the ray taken into the object's
    //   space by M⁻¹, the object's hit there, its normal brought back by
    //   (M⁻¹)ᵀ and normalised
    let local = Ray(
      origin: inverse.transformPoint(ray.origin),
      direction: inverse.transformDirection(ray.direction))
    guard var hit = object.intersect(local, after: tMin, before: tMax) else {
      return nil
    }
    hit.normal = inverse.transposed().transformDirection(hit.normal)
      .normalized()
    return hit
    // END SOLUTION
  }

  public var boundingBox: BoundingBox? {
    object.boundingBox?.transformed(by: matrix)
  }
}
