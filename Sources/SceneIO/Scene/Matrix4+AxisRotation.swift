import Geometry

// The readers' axis-angle rotation (`Rotate { axis … angle … }` and the
// plist's `rotate`): the course's own code never builds one, so it lives
// beside the readers rather than in the geometry the course compiles.
extension Matrix4 {
  /// Rotation by `degrees` about `axis` (any non-zero length; it is
  /// normalised), right-handed: looking down the axis towards the origin,
  /// the rotation is counter-clockwise. Rows c·I + (1 − c)·a·aᵀ + s·[a]×
  /// (Rodrigues): about the x, y and z axes, `rotationX`, `Y` and `Z` to
  /// within an ulp of 1 on the diagonal.
  /// A zero or non-finite axis gives NaN entries.
  static func rotation(
    axis: Vector3<Scalar>, degrees: Scalar
  ) -> Matrix4 {
    // Scaled to a largest component of 1 first: no square overflows or
    // underflows, whatever the axis's length.
    let largest = axis.maxMagnitude
    guard largest > 0, largest.isFinite else {
      return Matrix4(rows: [
        .nan, .nan, .nan, 0, .nan, .nan, .nan, 0, .nan, .nan, .nan, 0,
        0, 0, 0, 1,
      ])
    }
    let a = (axis / largest).normalized()
    let (c, s) = cosineAndSine(degrees: degrees)
    let k = 1 - c
    return Matrix4(rows: [
      c + k * a.x * a.x, k * a.x * a.y - s * a.z, k * a.x * a.z + s * a.y, 0,
      k * a.y * a.x + s * a.z, c + k * a.y * a.y, k * a.y * a.z - s * a.x, 0,
      k * a.z * a.x - s * a.y, k * a.z * a.y + s * a.x, c + k * a.z * a.z, 0,
      0, 0, 0, 1,
    ])
  }
}
