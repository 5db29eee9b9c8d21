import ExactArithmetic
import Geometry
import SceneDescription

/// The two ways of solving n·(o + t·d) = offset for t, shared by the
/// package `Plane` and the fast engine, as `SphereIntersection` is for
/// spheres.
@usableFromInline
package enum PlaneIntersection {
  /// The course's formula, t = (offset − n·o) / (n·d), in working
  /// precision. Both products cancel: the first for an origin near the
  /// plane, the second for a grazing ray.
  @inlinable @inline(__always)
  package static func naiveT<S: RayScalar>(
    normal n: Vector3<S>, offset: S, origin: Vector3<S>,
    direction d: Vector3<S>, after tMin: S, before tMax: S
  ) -> S? {
    let denominator = n.dot(d)
    guard denominator != 0 else { return nil }
    let t = (offset - n.dot(origin)) / denominator
    return t > tMin && t < tMax ? t : nil
  }

  /// t = k / (n·d), with the plane given relative to the ray's origin by
  /// k = offset − n·o (`CameraRelative.plane`, computed without
  /// cancellation) and n·d evaluated compensated where it cancels.
  ///
  /// n·d in working precision errs by at most γ₃·Σ|nᵢdᵢ| ≤ 4ε for unit
  /// vectors. Where |n·d| ≥ 1/4 that is a relative error of at most 16ε and
  /// the plain product stands; with tMin ≥ 0, a clear sign against the
  /// plane's side (t < 0) is a miss; only rays within about 15° of the
  /// plane, where n·d cancels, pay for the compensated product.
  ///
  /// - Parameters:
  ///   - normalTail: the digits of the scene's normal that `normal` could
  ///     not hold (zero when the render's precision is the scene's).
  ///   - isAxisAligned: one non-zero component and no tail: then n·d is a
  ///     single, correctly rounded product that never cancels.
  @inlinable @inline(__always)
  package static func stableT<S: RayScalar>(
    normal n: Vector3<S>, normalTail: Vector3<S>, distance k: S,
    isAxisAligned: Bool, direction d: Vector3<S>, after tMin: S,
    before tMax: S
  ) -> S? {
    let plain = n.dot(d)
    let denominator: S
    if plain.magnitude >= 0.25 || isAxisAligned {
      denominator = plain
    } else if tMin >= 0 && plain.magnitude > 8 * S.ulpOfOne
      && (plain > 0) != (k > 0)
    {
      return nil
    } else {
      denominator = Compensated.dot(n, d) + normalTail.dot(d)
    }
    guard denominator != 0 else { return nil }
    let t = k / denominator
    return t > tMin && t < tMax ? t : nil
  }

  /// Whether a normal has exactly one non-zero component.
  @inlinable
  package static func isAxisAligned<S: RayScalar>(_ n: Vector3<S>) -> Bool {
    (n.x != 0 ? 1 : 0) + (n.y != 0 ? 1 : 0) + (n.z != 0 ? 1 : 0) == 1
  }
}
