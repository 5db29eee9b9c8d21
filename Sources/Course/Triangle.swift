import Geometry

/// A triangle (a, b, c), with a normal and texture coordinates at each
/// vertex when its mesh gives them.
public struct Triangle: Hittable {
  public var a: Vector3<Double>
  public var b: Vector3<Double>
  public var c: Vector3<Double>
  /// Normals at a, b and c (not necessarily unit length), or nil for the
  /// flat normal of the winding.
  public var normals: (Vector3<Double>, Vector3<Double>, Vector3<Double>)?
  /// Texture coordinates at a, b and c, or nil.
  public var textureCoordinates:
    (
      TextureCoordinate<Double>, TextureCoordinate<Double>,
      TextureCoordinate<Double>
    )?
  public var materialIndex: Int

  public init(
    _ a: Vector3<Double>, _ b: Vector3<Double>, _ c: Vector3<Double>,
    materialIndex: Int = 0
  ) {
    self.a = a
    self.b = b
    self.c = c
    self.materialIndex = materialIndex
  }

  /// The hit in (tMin, tMax), or nil.
  ///
  /// The ray's point o + t·d is the triangle's point a + β(b − a) + γ(c − a)
  /// when β·(b − a) + γ·(c − a) − t·d = o − a: three equations in β, γ and
  /// t, solved by Cramer's rule (each determinant a scalar triple product).
  /// The point is inside when β ≥ 0, γ ≥ 0 and β + γ ≤ 1. The normal is
  /// the winding's, (b − a) × (c − a), not turned towards the ray; with
  /// vertex normals, their interpolation by (1 − β − γ, β, γ), normalised.
  public func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    // BEGIN SOLUTION week 5: triangles and meshes — β, γ and t by Cramer's
    //   rule, a hit when β ≥ 0, γ ≥ 0, β + γ ≤ 1 and t in (tMin, tMax); the
    //   winding's normal or the vertex normals' interpolation, normalised;
    //   the interpolated texture coordinates
    let edge1 = b - a
    let edge2 = c - a
    let s = ray.origin - a
    let p = ray.direction.cross(edge2)
    let determinant = edge1.dot(p)
    guard determinant != 0 else { return nil }  // parallel to the plane
    let beta = s.dot(p) / determinant
    let q = s.cross(edge1)
    let gamma = ray.direction.dot(q) / determinant
    let t = edge2.dot(q) / determinant
    guard beta >= 0, gamma >= 0, beta + gamma <= 1, tMin < t, t < tMax else {
      return nil
    }
    let alpha = 1 - beta - gamma
    let normal: Vector3<Double>
    if let (n0, n1, n2) = normals {
      normal = (n0 * alpha + n1 * beta + n2 * gamma).normalized()
    } else {
      normal = edge1.cross(edge2).normalized()
    }
    var hit = Hit(t: t, normal: normal, materialIndex: materialIndex)
    if let (t0, t1, t2) = textureCoordinates {
      hit.textureCoordinate = TextureCoordinate(
        t0.u * alpha + t1.u * beta + t2.u * gamma,
        t0.v * alpha + t1.v * beta + t2.v * gamma)
    }
    return hit
    // END SOLUTION
  }

  public var boundingBox: BoundingBox? { BoundingBox(around: a, b, c) }
}
