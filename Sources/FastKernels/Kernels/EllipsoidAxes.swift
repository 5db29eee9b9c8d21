import ExactArithmetic
import Geometry
import SceneDescription

/// The principal axes of an ellipsoid M·{P : |P − c| = r}: the world unit
/// directions u₀, u₁, u₂ and the semi-axis lengths A₀, A₁, A₂, so that a
/// world point X lies on it exactly when Σⱼ (uⱼ·(X − C) / Aⱼ)² = 1, with
/// C = M·c its centre. They are the singular value decomposition
/// L = U·diag(σ)·Vᵀ of the matrix's linear part L (Aⱼ = σⱼ·r, uⱼ the
/// columns of U), computed in DoubleDouble once per ellipsoid.
///
/// In this frame a ray's direction d becomes (uⱼ·d / Aⱼ)ⱼ: one dot product
/// of unit vectors and one quotient per axis, each accurate to a few ulps
/// of |d|/Aⱼ, as if d had moved by a few ulps, however flat the ellipsoid.
/// The rows of L⁻¹ (the course's way) mix the axes' scales: each row's dot
/// product with d loses ε·|d|/A_min, and the thin axis of a disc of aspect
/// 10⁸ swamps every digit of the other two in Float.
///
/// Accuracy. One-sided Jacobi (Hestenes: plane rotations applied to the
/// columns of L until they are orthogonal, L·V = U·diag(σ)) in
/// DoubleDouble, each rotation found from its two columns divided by powers
/// of two (exact) and stopped when every pair's cosine is below 2⁻¹⁰⁸. For
/// L = B·D (the columns carry the scales, B well conditioned: a scale
/// followed by a rotation) it is relatively accurate (Demmel and Veselić,
/// "Jacobi's method is more accurate than QR", SIAM J. Matrix Anal. Appl.
/// 13(4), 1992); measured against L's exact invariants, so it is for
/// L = D·B (a rotation followed by a scale) too: every σⱼ, the smallest as
/// well as the largest, within 2⁻¹⁰¹ relative, and every axis an
/// eigenvector of LLᵀ within 2⁻¹⁰³·σ_max², at every aspect up to 10³⁰⁰
/// (`EllipsoidAxesTests`). A matrix whose own rounding leaves it
/// ill-conditioned without a scaling is held to 2⁻¹⁰⁴·σ_max, below
/// Double's rounding of its entries while σ_max/σ_min < 2⁵⁰.
@usableFromInline
package struct EllipsoidAxes: Sendable {
  /// u₀, u₁, u₂: orthonormal to a few units of 2⁻¹⁰⁴.
  @usableFromInline
  package var directions: [Vector3<DoubleDouble>]
  /// A₀, A₁, A₂ > 0: the semi-axes, in the world's units.
  @usableFromInline
  package var lengths: [DoubleDouble]
  /// C = M·c, the centre in the world.
  @usableFromInline
  package var center: Vector3<DoubleDouble>

  /// The axes of `sphere` placed by `matrix` (affine); nil when a
  /// semi-axis is zero or not finite.
  @usableFromInline
  package init?(matrix m: Matrix4<Double>, sphere: Sphere<Double>) {
    typealias DD = DoubleDouble
    let rows = [
      Vector3(DD(m.m00), DD(m.m01), DD(m.m02)),
      Vector3(DD(m.m10), DD(m.m11), DD(m.m12)),
      Vector3(DD(m.m20), DD(m.m21), DD(m.m22)),
    ]
    let columns = (0..<3).map { j in
      Vector3(rows[0][j], rows[1][j], rows[2][j])
    }
    let c = Vector3<DD>(sphere.center)
    center = Vector3(
      DD(m.m03) + rows[0].dot(c), DD(m.m13) + rows[1].dot(c),
      DD(m.m23) + rows[2].dot(c))
    let radius = DD(sphere.radius)
    // L·V = W with orthogonal columns: L = Ŵ·diag|w|·Vᵀ, the world axes
    // are Ŵ's columns.
    var w = columns
    Self.orthogonalize(&w)
    var directions: [Vector3<DD>] = []
    var lengths: [DD] = []
    for j in 0..<3 {
      let length = Self.length(w[j])
      guard length > 0, length.isFinite else { return nil }
      directions.append(w[j] / length)
      lengths.append(length * radius)
    }
    guard lengths.allSatisfy({ $0 > 0 && $0.isFinite }) else { return nil }
    self.directions = directions
    self.lengths = lengths
  }

  /// 2^e as a DoubleDouble, exact for e within Double's normal range;
  /// zero below it.
  static func power(_ e: Int) -> DoubleDouble {
    guard e >= Double.leastNormalMagnitude.exponent else { return 0 }
    return DoubleDouble(Double(sign: .plus, exponent: e, significand: 1))
  }

  /// The exponent of the largest component's magnitude (0 for zero).
  static func exponent(_ v: Vector3<DoubleDouble>) -> Int {
    let largest = v.maxMagnitude
    return largest > 0 ? largest.exponent : 0
  }

  /// |v| with v divided by a power of two first, so that its square
  /// neither overflows nor underflows.
  static func length(_ v: Vector3<DoubleDouble>) -> DoubleDouble {
    let e = exponent(v)
    return (v * power(-e)).length * power(e)
  }

  /// Rotates pairs of `columns` until they are orthogonal to the working
  /// precision (one-sided Jacobi).
  ///
  /// Each rotation is found and applied with the columns' scales apart:
  /// with cᵢ = 2^eᵢ·bᵢ (bᵢ near unit, the power of two exact) and
  /// ρ = 2^−|eᵢ−eⱼ| ≤ 1, the tangent t = η/(1 + √(1 + η²)) of the angle
  /// that makes cᵢ and cⱼ orthogonal (η = 2γ/(β − α), α = |cᵢ|², β = |cⱼ|²,
  /// γ = cᵢ·cⱼ) is t = τ·ρ with τ from the scaled columns alone, and the
  /// rotated columns are cos·(cᵢ − τ·(ρ·cⱼ)) and cos·(cⱼ + τ·(ρ·cᵢ)): no
  /// square and no t leaves the normal range at any aspect, where t itself
  /// (ρ·γ/α ≈ 2⁻¹⁰⁰⁰ at an aspect of 10³⁰⁰) would be subnormal and lose the
  /// rotation's digits.
  static func orthogonalize(_ columns: inout [Vector3<DoubleDouble>]) {
    typealias DD = DoubleDouble
    // Orthogonal once the cosine of each pair's angle is below 2⁻¹⁰⁸:
    // within the rounding of the columns themselves. Jacobi converges
    // quadratically; 3×3 matrices take 3 to 5 sweeps.
    let tolerance = DD(0x1p-108)
    for _ in 0..<32 {
      var rotated = false
      for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let (ei, ej) = (exponent(columns[i]), exponent(columns[j]))
        let bi = columns[i] * power(-ei)
        let bj = columns[j] * power(-ej)
        let (alpha, beta, gamma) = (
          bi.lengthSquared, bj.lengthSquared, bi.dot(bj)
        )
        guard gamma.magnitude > tolerance * (alpha * beta).squareRoot()
        else { continue }
        // β − α = 4^max(eᵢ,eⱼ)·(denominator), 2γ = 2·4^max·ρ·γ′.
        let rho = power(-abs(ei - ej))
        let denominator =
          ei >= ej ? beta * rho * rho - alpha : beta - alpha * rho * rho
        let q = 2 * gamma / denominator
        let tau: DD =
          q.isFinite
          ? q / (1 + (1 + q * rho * q * rho).squareRoot())
          : (gamma > 0 ? 1 : -1) / rho
        guard tau != 0 else { continue }
        let cosine = 1 / (1 + tau * rho * tau * rho).squareRoot()
        let (a, b) = (columns[i], columns[j])
        columns[i] = (a - (b * rho) * tau) * cosine
        columns[j] = (b + (a * rho) * tau) * cosine
        rotated = true
      }
      if !rotated { return }
    }
  }
}
