/// Scalings of a matrix by powers of two, and its scale where it is a
/// similarity: what placing and rescaling a scene ask of it.
extension Matrix4 {
  /// S·M for S = diag(f, f, f, 1): the first three rows times f.
  package func rowsScaled(by f: Scalar) -> Matrix4 {
    var m = self
    m.m00 *= f; m.m01 *= f; m.m02 *= f; m.m03 *= f
    m.m10 *= f; m.m11 *= f; m.m12 *= f; m.m13 *= f
    m.m20 *= f; m.m21 *= f; m.m22 *= f; m.m23 *= f
    return m
  }

  /// The matrix with its rows scaled by a power of two that brings its
  /// largest linear entry near 1, when that entry is beyond 2^±30; itself
  /// otherwise. Its cofactors (`cofactorNormal`) then stay in range, their
  /// directions exactly those of the matrix's.
  package func withLinearPartNearOne() -> Matrix4 {
    let largest = Swift.max(
      m00.magnitude, m01.magnitude, m02.magnitude, m10.magnitude,
      m11.magnitude, m12.magnitude, m20.magnitude, m21.magnitude,
      m22.magnitude)
    guard largest > 0, largest.isFinite else { return self }
    let exponent = Int(largest.exponent)
    guard !(-30...30).contains(exponent) else { return self }
    return rowsScaled(
      by: Scalar(
        sign: .plus, exponent: Scalar.Exponent(-exponent),
        significand: 1))
  }

  /// M·S for S = diag(f, f, f, 1): the first three columns times f.
  package func columnsScaled(by f: Scalar) -> Matrix4 {
    var m = self
    m.m00 *= f; m.m01 *= f; m.m02 *= f
    m.m10 *= f; m.m11 *= f; m.m12 *= f
    m.m20 *= f; m.m21 *= f; m.m22 *= f
    m.m30 *= f; m.m31 *= f; m.m32 *= f
    return m
  }

  /// s when the linear part is s times a rotation (LᵀL = s²·I to within
  /// 16 ε relative) and the matrix is affine: a sphere then stays a sphere
  /// of radius r·s, and is best kept as one.
  @usableFromInline
  package var similarityScale: Scalar? {
    guard isAffine else { return nil }
    let columns = [
      Vector3(m00, m10, m20), Vector3(m01, m11, m21), Vector3(m02, m12, m22),
    ]
    let squared = columns[0].lengthSquared
    guard squared > 0, squared.isFinite else { return nil }
    let tolerance = 16 * Scalar.ulpOfOne * squared
    for i in 0..<3 {
      for j in 0..<3 {
        let product = columns[i].dot(columns[j])
        let expected: Scalar = i == j ? squared : 0
        if (product - expected).magnitude > tolerance { return nil }
      }
    }
    return squared.squareRoot()
  }
}
