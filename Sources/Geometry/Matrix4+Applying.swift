// MARK: - Applying

extension Matrix4 {
  /// M·(p, 1), divided by the resulting w when the matrix is not affine.
  ///
  /// For an affine matrix (the usual case) no division happens, so
  /// translations and scales by powers of two are exact. A projective matrix
  /// that sends p to w = 0 (a point at infinity) gives non-finite components.
  @inlinable
  @_specialize(where Scalar == Double)
  public func transformPoint(_ p: Vector3<Scalar>) -> Vector3<Scalar> {
    let x = m00 * p.x + m01 * p.y + m02 * p.z + m03
    let y = m10 * p.x + m11 * p.y + m12 * p.z + m13
    let z = m20 * p.x + m21 * p.y + m22 * p.z + m23
    if isAffine { return Vector3(x, y, z) }
    let w = m30 * p.x + m31 * p.y + m32 * p.z + m33
    return Vector3(x / w, y / w, z / w)
  }

  /// M·(d, 0): the upper-left 3×3 applied to d, ignoring the translation.
  /// The result is not normalised, so that a ray's t means the same point
  /// before and after (as the course's `Transform` does). For a projective
  /// matrix this is the w = 0 convention, not the derivative of
  /// `transformPoint`.
  @inlinable
  @_specialize(where Scalar == Double)
  public func transformDirection(_ d: Vector3<Scalar>) -> Vector3<Scalar> {
    Vector3(
      m00 * d.x + m01 * d.y + m02 * d.z,
      m10 * d.x + m11 * d.y + m12 * d.z,
      m20 * d.x + m21 * d.y + m22 * d.z)
  }

  /// The unit normal of a surface transformed by this matrix, given its
  /// normal n before: the direction of (L⁻¹)ᵀ·n, L the upper-left 3×3, so
  /// that it stays perpendicular to every transformed tangent L·t.
  ///
  /// Computed as sign(det L)·cof(L)·n (cof(L) = det L·(L⁻¹)ᵀ, its rows the
  /// cross products of L's rows), so no inverse is needed and no division
  /// by a tiny determinant happens; the sign keeps a mirroring transform
  /// from turning the normal inside out. Each component is within a few
  /// ulps of the largest (cancellation only where the exact component is
  /// small). A zero normal, or a flattening L that maps n to 0, gives NaNs;
  /// objects under such a transform have no inverse and are never hit.
  /// The cofactors are quadratic in L's entries, so entries beyond about
  /// 10¹⁵⁰ (Double) or 10¹⁹ (Float) overflow them.
  @inlinable
  public func transformNormal(_ n: Vector3<Scalar>) -> Vector3<Scalar> {
    cofactorNormal(n).normalized()
  }

  /// sign(det L)·cof(L)·n, not normalised: `transformNormal` before its
  /// normalisation. Every normal is scaled by the same |det L|, so vertex
  /// normals moved this way interpolate, then normalise, to the transform
  /// of the interpolated normal (as a hit's normal is moved in the course:
  /// interpolate in object space, then transform).
  @inlinable
  public func cofactorNormal(_ n: Vector3<Scalar>) -> Vector3<Scalar> {
    let r0 = Vector3(m00, m01, m02)
    let r1 = Vector3(m10, m11, m12)
    let r2 = Vector3(m20, m21, m22)
    let c0 = r1.cross(r2)
    let determinant = r0.dot(c0)
    let sign: Scalar = determinant < 0 ? -1 : 1
    let cofactor = Vector3(c0.dot(n), r2.cross(r0).dot(n), r0.cross(r1).dot(n))
    return cofactor * sign
  }
}

extension Matrix4: CustomStringConvertible {
  public var description: String {
    "[\(m00) \(m01) \(m02) \(m03); \(m10) \(m11) \(m12) \(m13); "
      + "\(m20) \(m21) \(m22) \(m23); \(m30) \(m31) \(m32) \(m33)]"
  }
}
