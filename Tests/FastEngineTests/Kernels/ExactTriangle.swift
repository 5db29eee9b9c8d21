@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Exact references for triangles, in `ExactDyadic` (exact dyadic
/// rationals, independent of the project's error-free transformations).

/// The exact t at which the ray from `origin` along `direction` meets the
/// plane of triangle (v0, v1, v2), det[e1, e2, v0 − o] / det[e1, e2, d]
/// with e1 = v1 − v0, e2 = v2 − v0, and the ray's barycentric weights of
/// v0, v1, v2 (each d·((vⱼ − o) × (vₖ − o)) over their sum, to a few
/// ulps): every entry and product exact. Nil for a ray parallel to the
/// plane or a degenerate triangle.
func exactTriangleT(
  _ v0: Vector3<Double>, _ v1: Vector3<Double>, _ v2: Vector3<Double>,
  origin: Vector3<Double>, direction: Vector3<Double>
) -> (hi: Double, lo: Double, weights: (Double, Double, Double))? {
  typealias Exact3 = [ExactDyadic]
  func exact(_ v: Vector3<Double>) -> Exact3 {
    [ExactDyadic(v.x), ExactDyadic(v.y), ExactDyadic(v.z)]
  }
  func minus(_ a: Exact3, _ b: Exact3) -> Exact3 {
    (0..<3).map { a[$0] - b[$0] }
  }
  func cross(_ a: Exact3, _ b: Exact3) -> Exact3 {
    [
      a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
      a[0] * b[1] - a[1] * b[0],
    ]
  }
  func dot(_ a: Exact3, _ b: Exact3) -> ExactDyadic {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
  }
  let (p0, p1, p2, o, d) = (
    exact(v0), exact(v1), exact(v2), exact(origin), exact(direction)
  )
  let n = cross(minus(p1, p0), minus(p2, p0))
  let numerator = dot(n, minus(p0, o))
  let denominator = dot(n, d)
  guard !denominator.isZero else { return nil }
  let t = (ScaledDoubleDouble(numerator) / ScaledDoubleDouble(denominator))
    .value
  let (q0, q1, q2) = (minus(p0, o), minus(p1, o), minus(p2, o))
  let sum = ScaledDoubleDouble(denominator)
  func weight(_ a: Exact3, _ b: Exact3) -> Double {
    (ScaledDoubleDouble(dot(d, cross(a, b))) / sum).value.hi
  }
  let weights = (weight(q1, q2), weight(q2, q0), weight(q0, q1))
  return (t.hi, t.lo, weights)
}
