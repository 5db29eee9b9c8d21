import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

// Helpers of the fast engine's tests: reference intersections computed in
// the widest precision the platform has, and renders compared bit for bit.

// MARK: - Reference intersections

/// A hit computed in ReferenceScalar.
struct ReferenceHit {
  var t: ReferenceScalar
  var normal: Vector3<ReferenceScalar>
}

/// The nearest root in (tMin, tMax) of |o + t·d − centre| = r, from the exact
/// values of T's inputs, in ReferenceScalar, by the cancellation-free form
/// (closest approach l = p − (s/a)·d, q = s + sign(s)·√(a(r² − |l|²)),
/// roots q/a and c/q), written out here independently of the library.
///
/// Accurate to a few ReferenceScalar ulps of t (64 bits against Double's 53)
/// away from the silhouette, provided c = |p|² − r² (p = centre − o) is
/// accurate relative to itself: c carries an absolute error of about
/// 2^−64·|p|², which matters only when the origin is close to a huge
/// sphere. There c is exact for Float inputs (24-bit products are exact in
/// 64 bits) and for Double inputs whose coordinates and radius are integers
/// below 2^31, so the planet tests use such inputs.
///
/// The normal is (o + t·d − centre)/r, whose cancellation costs
/// 2^−64·|p|/r: negligible for Float below L/r = 10^6 and for Double below
/// L/r = 10^2, and meaningless beyond.
func referenceIntersect<T: RayScalar>(
  _ ray: Ray<T>, _ sphere: Sphere<T>, after tMin: T = 0,
  before tMax: T = .infinity
) -> ReferenceHit? {
  typealias R = ReferenceScalar
  let o = Vector3<R>(ray.origin)
  let d = Vector3<R>(ray.direction)
  let centre = Vector3<R>(sphere.center)
  let r = R(sphere.radius)
  let p = centre - o
  let a = d.lengthSquared
  let s = p.dot(d)
  let l = p - d * (s / a)
  let reduced = r * r - l.lengthSquared
  guard reduced >= 0 else { return nil }
  let root = (a * reduced).squareRoot()
  let q = s >= 0 ? s + root : s - root
  let c = p.lengthSquared - r * r
  let roots = [q / a, c / q].sorted()
  guard
    let t = roots.first(where: { $0 > R(tMin) && $0 < R(tMax) })
  else { return nil }
  let normal = (o + d * t - centre) / r
  return ReferenceHit(t: t, normal: normal)
}

/// t = (offset − n·o) / (n·d) for the plane's stored (already normalised)
/// normal and offset, in ReferenceScalar; nil when n·d = 0 or t is outside
/// (tMin, tMax). Exact but for the final roundings for Float inputs (24-bit
/// products are exact in 64 bits); for Double inputs each sum carries an
/// absolute error of about 2^−64 times its largest term.
func referenceIntersect<T: RayScalar>(
  _ ray: Ray<T>, _ plane: Plane<T>, after tMin: T = 0,
  before tMax: T = .infinity
) -> ReferenceHit? {
  typealias R = ReferenceScalar
  let n = Vector3<R>(plane.normal)
  let denominator = n.dot(Vector3<R>(ray.direction))
  guard denominator != 0 else { return nil }
  let t = (R(plane.offset) - n.dot(Vector3<R>(ray.origin))) / denominator
  guard t > R(tMin) && t < R(tMax) else { return nil }
  return ReferenceHit(t: t, normal: n)
}

// MARK: - Renders

/// The number of pixels where two renders of one size differ in any
/// output, bit for bit.
func differences<S: RayScalar>(_ a: RenderBuffers<S>, _ b: RenderBuffers<S>)
  -> Int
{
  var count = 0
  for pixel in 0..<(a.width * a.height) {
    var same = true
    if !a.depth.isEmpty { same = same && a.depth[pixel] == b.depth[pixel] }
    if !a.normals.isEmpty {
      same = same && a.normals[pixel] == b.normals[pixel]
    }
    if !a.color.isEmpty { same = same && a.color[pixel] == b.color[pixel] }
    if !same { count += 1 }
  }
  return count
}

/// `camera` as `style` builds its rays (`RenderSettings.camera`).
func styled<S: RayScalar>(_ camera: PerspectiveCamera<S>, _ style: ImageStyle)
  -> PerspectiveCamera<S>
{
  RenderSettings(width: 1, height: 1, outputs: [], style: style).camera(camera)
}

extension RenderBuffers<Double> {
  /// Every value's bits and every byte, output by output: equal for two
  /// renders only if they are the same bit for bit.
  var bits: [[UInt64]] {
    [
      depth.map(\.bitPattern),
      normals.flatMap { [$0.x, $0.y, $0.z] }.map(\.bitPattern),
      color.flatMap { [$0.x, $0.y, $0.z] }.map(\.bitPattern),
      normalBytes.map(UInt64.init),
      colorBytes.map(UInt64.init),
    ]
  }
}
