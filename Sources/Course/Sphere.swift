import Geometry

/// A sphere: every point at distance `radius` from `center`.
public struct Sphere: Hittable {
  public var center: Vector3<Double>
  public var radius: Double
  public var materialIndex: Int

  public init(center: Vector3<Double>, radius: Double, materialIndex: Int = 0) {
    self.center = center
    self.radius = radius
    self.materialIndex = materialIndex
  }

  /// The nearest hit in (tMin, tMax), or nil.
  ///
  /// A point o + t·d of the ray is on the sphere when |o + t·d − c|² = r²,
  /// the quadratic a·t² + 2·b·t + c = 0 below (b is half the usual b).
  /// Two of the textbook's steps lose every digit on some scenes, and are
  /// written in forms that do not:
  /// - b² − a·c cancels for a small sphere far away; it equals a·(r² − |v|²)
  ///   with v the ray's closest approach to the centre, whose factors
  ///   (r − |v|)(r + |v|) do not cancel.
  /// - (−b ± √Δ)/a cancels for one of the two roots; q = −(b + sign(b)·√Δ)
  ///   never does, and the roots are q/a and c/q.
  ///
  /// A tangent ray hits at its double root; a ray from inside hits the far
  /// side. The normal is outward and unit length. Scenes of extreme range
  /// (a camera one unit above a planet, a speck 10⁸ radii away) are the
  /// other engine's job (docs/ENGINES.md): c below still cancels there.
  public func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    // BEGIN SOLUTION week 2: spheres and normals — the nearest root of
    //   |o + t·d − c|² = r² in (tMin, tMax) and the outward unit normal there
    let d = ray.direction
    let f = ray.origin - center  // from the centre to the ray's origin
    let a = d.dot(d)
    let b = f.dot(d)
    let c = f.dot(f) - radius * radius
    let v = f - d * (b / a)  // from the centre to the closest approach
    let distance = v.length
    let discriminant = a * (radius - distance) * (radius + distance)
    guard discriminant >= 0 else { return nil }  // the ray misses
    let q = -(b + Double(signOf: b, magnitudeOf: discriminant.squareRoot()))
    let (near, far) = (min(q / a, c / q), max(q / a, c / q))
    let t = tMin < near ? near : far  // the nearer root, unless behind
    guard tMin < t && t < tMax else { return nil }
    let normal = (f + d * t).normalized()
    return Hit(t: t, normal: normal, materialIndex: materialIndex)
    // END SOLUTION
  }

  public var boundingBox: BoundingBox? {
    let reach = Vector3(radius, radius, radius)
    return BoundingBox(lower: center - reach, upper: center + reach)
  }
}
