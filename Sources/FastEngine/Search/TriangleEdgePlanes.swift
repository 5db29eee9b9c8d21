import Geometry
import SceneDescription

/// A conservative first look at whether a ray from the eye misses a
/// triangle: the three planes through the eye and each of its edges, and
/// for each a margin past which the watertight test
/// (`TriangleIntersection`) is certain to find the same side. A ray that
/// lies beyond one plane and before another by more than their margins
/// passes outside the triangle, as that test computes it, so the screen
/// tiles skip its test: three dot products instead of the shear of three
/// vertices, and the nearest hit, its weights and ties unchanged, since
/// only tests that would have missed are skipped.
///
/// With A, B, C the corners relative to the eye and d the ray's direction,
/// the exact edge functions are det(d, B, C), det(d, C, A) and
/// det(d, A, B), that is d·(B × C) and so on; the watertight test's u, v
/// and w are these divided by d's largest component (the frame's kz),
/// all with one sign, so a ray is inside when they agree in sign.
///
/// Rounding, in units of ε = `S.ulpOfOne`, with ‖·‖₁ the sum of
/// magnitudes and |d| ≤ 2: the test's sheared coordinates each err by at
/// most 8ε‖B‖₁ (one subtraction from the eye, a rounded shear of at most
/// 1 times the kz coordinate, one subtraction), so u, two products of
/// them subtracted, errs by at most 36ε‖B‖₁‖C‖₁ (and its exact
/// recomputation when a function rounds to 0 is closer still); times
/// |d_kz| ≤ 2 that is 72ε‖B‖₁‖C‖₁ on the scale of det(d, B, C). The
/// normals here and their dot products with d err by at most
/// 16ε‖B‖₁‖C‖₁. The margin is 256ε‖B‖₁‖C‖₁, three times their sum, plus
/// 64 times the least normal magnitude for products that lose digits to
/// underflow. The bound does not assume the ray comes near the triangle;
/// near it, the real error is smaller by about the triangle's angular size.
struct TriangleEdgePlanes<S: RayScalar>: Sendable {
  /// B × C, C × A and A × B: the planes' normals.
  let normals: (Vector3<S>, Vector3<S>, Vector3<S>)
  /// Each plane's margin on d·normal.
  let margins: (S, S, S)

  /// The planes of the triangle with corners `v0`, `v1`, `v2` seen from
  /// `origin`, the origin of the rays to be tested; nil when a margin is
  /// not finite (the dot products might overflow), and no ray is skipped.
  @inline(__always)
  init?(
    _ v0: Vector3<S>, _ v1: Vector3<S>, _ v2: Vector3<S>, origin: Vector3<S>
  ) {
    let (a, b, c) = (v0 - origin, v1 - origin, v2 - origin)
    func size(_ p: Vector3<S>) -> S {
      p.x.magnitude + p.y.magnitude + p.z.magnitude
    }
    let sizes = (size(a), size(b), size(c))
    let products = (sizes.1 * sizes.2, sizes.2 * sizes.0, sizes.0 * sizes.1)
    guard products.0.isFinite, products.1.isFinite, products.2.isFinite else {
      return nil
    }
    let scale = 256 * S.ulpOfOne
    let floor = 64 * S.leastNormalMagnitude
    normals = (b.cross(c), c.cross(a), a.cross(b))
    margins = (
      scale * products.0 + floor, scale * products.1 + floor,
      scale * products.2 + floor
    )
  }

  /// True when the watertight test of the ray from `origin` (given to
  /// `init`) along `direction` is certain to miss the triangle.
  ///
  /// - Precondition: |direction| ≤ 2 (camera rays are unit vectors).
  @inline(__always)
  func excludes(_ direction: Vector3<S>) -> Bool {
    let sides = (
      direction.dot(normals.0), direction.dot(normals.1),
      direction.dot(normals.2)
    )
    let below =
      sides.0 < -margins.0 || sides.1 < -margins.1 || sides.2 < -margins.2
    let above =
      sides.0 > margins.0 || sides.1 > margins.1 || sides.2 > margins.2
    return below && above
  }
}
