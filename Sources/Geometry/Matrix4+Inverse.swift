// MARK: - Inverse

extension Matrix4 {
  /// The pivot below which `inverse()` calls the matrix singular, relative
  /// to the equilibrated matrix (every row's and column's largest entry in
  /// [1, 2)): 128ε. Gauss–Jordan on such a 4×4 grows entries by at most
  /// 2³ (partial pivoting), so rounding leaves noise of a few tens of ε
  /// where a pivot of an exactly singular matrix should be 0; a pivot below
  /// 128ε cannot be told from that noise, and the inverse's condition number
  /// would exceed about 1/(128ε), leaving it no reliable digit.
  public static var singularPivotThreshold: Scalar { 128 * Scalar.ulpOfOne }

  /// The inverse, or nil when the matrix is singular or too close to it to
  /// invert in this precision (see `singularPivotThreshold`), or has a
  /// non-finite entry, or its inverse would overflow.
  ///
  /// An affine matrix [L t; 0 1] is inverted as [L⁻¹ −L⁻¹t; 0 1], so its
  /// translation neither affects whether it is invertible nor mixes into
  /// L⁻¹'s rounding; any other matrix is inverted whole. Either way by
  /// Gauss–Jordan elimination with partial pivoting, after scaling each row
  /// and then each column by a power of two (exactly) so that its largest
  /// entry lies in [1, 2): the singularity test is then independent of the
  /// units (`Scale 1e-20 1e-20 1e-20` is as invertible as `Scale 1 1 1`).
  ///
  /// Error: normwise, ‖M⁻¹·M − I‖ is within a small multiple of nε·κ(M)
  /// (n = 3 for the linear part of an affine matrix, 4 otherwise; κ the
  /// ∞-norm condition number), and the translation column of M⁻¹·M is 0
  /// within a few ε of |L⁻¹|·|t|. See Matrix4Tests for the measured
  /// constants.
  public func inverse() -> Matrix4? {
    let entries = rowMajorEntries
    guard entries.allSatisfy(\.isFinite) else { return nil }
    guard isAffine else {
      guard let inverse = Self.equilibratedInverse(entries, size: 4) else {
        return nil
      }
      return Matrix4(rows: inverse)
    }
    let linear = [m00, m01, m02, m10, m11, m12, m20, m21, m22]
    guard let l = Self.equilibratedInverse(linear, size: 3) else { return nil }
    let t = Vector3(m03, m13, m23)
    let result = Matrix4(
      l[0], l[1], l[2], -(l[0] * t.x + l[1] * t.y + l[2] * t.z),
      l[3], l[4], l[5], -(l[3] * t.x + l[4] * t.y + l[5] * t.z),
      l[6], l[7], l[8], -(l[6] * t.x + l[7] * t.y + l[8] * t.z),
      0, 0, 0, 1)
    guard result.rowMajorEntries.allSatisfy(\.isFinite) else { return nil }
    return result
  }

  /// The inverse of a row-major size×size matrix, by Gauss–Jordan on its
  /// power-of-two equilibration B = R·A·C, A⁻¹ = C·B⁻¹·R; nil when a pivot
  /// is below `singularPivotThreshold` or an entry of the inverse is not
  /// finite.
  private static func equilibratedInverse(
    _ matrix: [Scalar], size n: Int
  ) -> [Scalar]? {
    var a = matrix
    var rowExponent = [Int](repeating: 0, count: n)
    var columnExponent = [Int](repeating: 0, count: n)
    for row in 0..<n {
      let largest = (0..<n).map { a[n * row + $0].magnitude }.max() ?? 0
      guard largest > 0 else { return nil }
      rowExponent[row] = -Int(largest.exponent)
      for column in 0..<n {
        a[n * row + column] = scaled(a[n * row + column], rowExponent[row])
      }
    }
    for column in 0..<n {
      let largest = (0..<n).map { a[n * $0 + column].magnitude }.max() ?? 0
      guard largest > 0 else { return nil }
      columnExponent[column] = -Int(largest.exponent)
      for row in 0..<n {
        a[n * row + column] = scaled(
          a[n * row + column], columnExponent[column])
      }
    }
    guard var inverse = gaussJordanInverse(a, size: n) else { return nil }
    for row in 0..<n {
      for column in 0..<n {
        // (C·B⁻¹·R)[i][j] = c_i · B⁻¹[i][j] · r_j.
        let value = scaled(
          inverse[n * row + column], columnExponent[row] + rowExponent[column])
        guard value.isFinite else { return nil }
        inverse[n * row + column] = value
      }
    }
    return inverse
  }

  /// x·2^k, exact unless the result leaves the normal range.
  private static func scaled(_ x: Scalar, _ k: Int) -> Scalar {
    Scalar(sign: .plus, exponent: Scalar.Exponent(k), significand: x)
  }

  /// The inverse of an equilibrated row-major size×size matrix, or nil
  /// when a pivot is below `singularPivotThreshold`.
  private static func gaussJordanInverse(
    _ matrix: [Scalar], size n: Int
  ) -> [Scalar]? {
    var a = matrix
    var inverse = [Scalar](repeating: 0, count: n * n)
    for diagonal in 0..<n { inverse[n * diagonal + diagonal] = 1 }
    for column in 0..<n {
      // The largest remaining entry of the column keeps multipliers ≤ 1.
      var pivotRow = column
      for row in (column + 1)..<n
      where a[n * row + column].magnitude > a[n * pivotRow + column].magnitude {
        pivotRow = row
      }
      let pivot = a[n * pivotRow + column]
      guard pivot.magnitude >= singularPivotThreshold else { return nil }
      if pivotRow != column {
        for k in 0..<n {
          a.swapAt(n * pivotRow + k, n * column + k)
          inverse.swapAt(n * pivotRow + k, n * column + k)
        }
      }
      for k in 0..<n {
        a[n * column + k] /= pivot
        inverse[n * column + k] /= pivot
      }
      for row in 0..<n where row != column {
        let factor = a[n * row + column]
        guard factor != 0 else { continue }
        for k in 0..<n {
          a[n * row + k] -= factor * a[n * column + k]
          inverse[n * row + k] -= factor * inverse[n * column + k]
        }
      }
    }
    return inverse
  }
}
