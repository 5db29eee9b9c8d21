@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The exact intersection of a ray E + t·d (E and d exactly as given, in
/// Double or Float) with the ellipsoid M·{P : |P − c| = r} of a scene's
/// Double matrix M = [L | T], for accuracy tests: formulated in world
/// space against the exact inverse of the quadric and computed in exact
/// rational arithmetic (`ExactDyadic`), sharing nothing with the engine.
///
/// With adj = det(L)·L⁻¹ (L's adjugate, exact), C = T + L·c, w = C − E,
/// u = adj·d, v = adj·w, a point X is on the ellipsoid when
/// |adj·(X − C)|² = K = r²·det², so along the ray
/// α t² − 2β t + γ = 0 with α = |u|², β = u·v, γ = |v|² − K, all exact.
/// The discriminant Δ = β² − αγ is exact, so hit or miss is decided
/// exactly. The roots t = γ/(β + √Δ) (the eye outside, entering) and
/// (β + √Δ)/α (inside) and the normal, the gradient
/// adjᵀ·adj·(X − C) ∝ −(adjᵀ(αv − βu) ± √Δ·adjᵀu) with αv − βu ⊥ u, need
/// √Δ and nothing cancels after it: they are converted to DoubleDouble
/// (`ScaledDoubleDouble`) only then, with a relative error of a few 2⁻¹⁰⁴.
struct ExactEllipsoid {
  typealias Exact = ExactDyadic
  typealias Scaled = ScaledDoubleDouble

  let adjugate: [[Exact]]
  let center: [Exact]
  /// K = r²·det².
  let k: Exact

  init(matrix m: Matrix4<Double>, sphere: Sphere<Double>) {
    let l = [
      [m.m00, m.m01, m.m02], [m.m10, m.m11, m.m12], [m.m20, m.m21, m.m22],
    ].map { $0.map(Exact.init) }
    // adj[i][j] = the cofactor of l[j][i].
    func minor(_ r0: Int, _ r1: Int, _ c0: Int, _ c1: Int) -> Exact {
      l[r0][c0] * l[r1][c1] - l[r0][c1] * l[r1][c0]
    }
    adjugate = [
      [minor(1, 2, 1, 2), -minor(0, 2, 1, 2), minor(0, 1, 1, 2)],
      [-minor(1, 2, 0, 2), minor(0, 2, 0, 2), -minor(0, 1, 0, 2)],
      [minor(1, 2, 0, 1), -minor(0, 2, 0, 1), minor(0, 1, 0, 1)],
    ]
    let determinant =
      l[0][0] * adjugate[0][0] + l[0][1] * adjugate[1][0]
      + l[0][2] * adjugate[2][0]
    let c = [sphere.center.x, sphere.center.y, sphere.center.z].map(
      Exact.init)
    let translation = [m.m03, m.m13, m.m23].map(Exact.init)
    center = (0..<3).map { i in
      translation[i] + l[i][0] * c[0] + l[i][1] * c[1] + l[i][2] * c[2]
    }
    let r = Exact(sphere.radius)
    k = r * r * determinant * determinant
  }

  static func dot(_ a: [Exact], _ b: [Exact]) -> Exact {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
  }

  func adjugateTimes(_ x: [Exact]) -> [Exact] {
    adjugate.map { Self.dot($0, x) }
  }

  func adjugateTransposeTimes(_ x: [Exact]) -> [Exact] {
    (0..<3).map { j in
      adjugate[0][j] * x[0] + adjugate[1][j] * x[1] + adjugate[2][j] * x[2]
    }
  }

  /// What the exact intersection says about one ray.
  struct Result {
    /// Δ ≥ 0 and a root in (0, ∞).
    var hit: Bool
    /// The root hit, to a few 2⁻¹⁰⁴ relative; nil on a miss.
    var t: DoubleDouble?
    /// The outward unit normal there, each component to a few 2⁻¹⁰⁴.
    var normal: Vector3<DoubleDouble>?
    /// |Δ| over its first-order change when d moves by |d| and the eye's
    /// offset w = C − E by its own component along each of the
    /// ellipsoid's axes aⱼ (|∂Δ/∂d|·|d| + Σⱼ |∂Δ/∂w·aⱼ|·|aⱼ·w|): how many
    /// relative roundings of the ray's direction or of the ellipsoid's
    /// position in its own frame away from the silhouette the ray is.
    /// Below a few ε: the rim.
    var rimDistance: Double
  }

  /// The exact intersection of the ray from `eye` along `direction`;
  /// `axes` (the ellipsoid's, roughly) only scale `rimDistance`.
  func intersect(
    eye: Vector3<Double>, direction: Vector3<Double>, axes: [Vector3<Double>]
  ) -> Result {
    let e = [eye.x, eye.y, eye.z].map(Exact.init)
    let d = [direction.x, direction.y, direction.z].map(Exact.init)
    let w = (0..<3).map { center[$0] - e[$0] }
    let u = adjugateTimes(d)
    let v = adjugateTimes(w)
    let alpha = Self.dot(u, u)
    let beta = Self.dot(u, v)
    let gamma = Self.dot(v, v) - k
    let discriminant = beta * beta - alpha * gamma
    // αv − βu: the closest approach, scaled, exactly ⊥ u.
    let approach = (0..<3).map { alpha * v[$0] - beta * u[$0] }
    let a = adjugateTransposeTimes(approach)
    let rim = rimDistance(
      discriminant: discriminant, gamma: gamma, beta: beta, u: u, v: v,
      a: a, d: d, w: w, axes: axes)
    let outside = gamma.signum > 0
    guard discriminant.signum >= 0, !outside || beta.signum > 0,
      gamma.signum != 0
    else {
      return Result(hit: false, t: nil, normal: nil, rimDistance: rim)
    }
    let root = Scaled(discriminant).squareRoot()
    let t =
      outside
      ? Scaled(gamma) / (Scaled(beta) + root)
      : (Scaled(beta) + root) / Scaled(alpha)
    let b = adjugateTransposeTimes(u)
    // −(A ± √Δ·B): + entering (outside), − leaving (inside).
    let side = outside ? root : -root
    let gradient = (0..<3).map { -(Scaled(a[$0]) + side * Scaled(b[$0])) }
    return Result(
      hit: true, t: t.value, normal: Self.unit(gradient), rimDistance: rim)
  }

  /// |Δ| / (|∂Δ/∂d|·|d| + Σⱼ |∂Δ/∂w·aⱼ|·|aⱼ·w|), with
  /// ∂Δ/∂d = 2adjᵀ(βv − γu) and ∂Δ/∂w = −2adjᵀ(αv − βu) (from
  /// ∂α/∂d = 2adjᵀu, ∂β/∂d = adjᵀv, ∂β/∂w = adjᵀu, ∂γ/∂w = 2adjᵀv), in
  /// Double.
  func rimDistance(
    discriminant: Exact, gamma: Exact, beta: Exact, u: [Exact], v: [Exact],
    a: [Exact], d: [Exact], w: [Exact], axes: [Vector3<Double>]
  ) -> Double {
    let byDirection = adjugateTransposeTimes(
      (0..<3).map { beta * v[$0] - gamma * u[$0] })
    var sensitivity = Scaled(2) * Self.length(byDirection) * Self.length(d)
    for axis in axes {
      let along = [axis.x, axis.y, axis.z].map(Exact.init)
      sensitivity =
        sensitivity + Scaled(2) * Scaled(Self.dot(a, along)).magnitude
        * Scaled(Self.dot(w, along)).magnitude
    }
    guard !sensitivity.isZero else { return .infinity }
    let ratio = Scaled(discriminant).magnitude / sensitivity
    return Double(ratio.value.hi)
  }

  static func length(_ x: [Exact]) -> Scaled {
    let scaled = x.map(Scaled.init)
    return (scaled[0] * scaled[0] + scaled[1] * scaled[1] + scaled[2]
      * scaled[2]).squareRoot()
  }

  /// The unit vector along x, in DoubleDouble.
  static func unit(_ x: [Scaled]) -> Vector3<DoubleDouble> {
    let top = x.filter { !$0.isZero }.map(\.exponent).max() ?? 0
    let v = x.map { ($0 * Scaled(significand: 1, exponent: -top)).value }
    let vector = Vector3(v[0], v[1], v[2])
    return vector / vector.length
  }
}

extension ScaledDoubleDouble {
  init(_ value: Int) { self.init(DoubleDouble(value)) }
}
