import Geometry
import SceneDescription

/// A camera ray's test of an ellipsoid in its unit-sphere frame
/// (`EllipsoidFrame`): the stable quadratic of `SphereIntersection`, with
/// the closest approach taken from a cross product, where it does not
/// cancel.
///
/// In this frame a flat ellipsoid is a unit sphere seen from far away
/// along a direction D that is nearly its thin axis: a disc of aspect 10⁸
/// seen from 2 radii puts the eye 2·10⁸ radii from the sphere. There the
/// closest approach l = p − (s/a)·D, computed component by component,
/// loses ε·|p| in every component to the cancellation of p against
/// (s/a)·D, 12 radii in Float: the hit is lost or the normal reversed,
/// though the ray, perturbed by ε in the world, moves l by only
/// ε·(distance travelled / the disc's radius). Here the discriminant is
/// a·(1 − |l|²) = a − |p × D|² (|p × D|² = a|p|² − s²) and l itself is
/// (D × (p × D))/a. With p = τD + l, each component pᵢDⱼ − pⱼDᵢ of p × D is
/// lᵢDⱼ − lⱼDᵢ, formed from products of at most τ|Dᵢ||Dⱼ| + |l||D|: its
/// rounding moves l by ε·(τ|Dᵢ| + |l|) in axis i, the ray's own travel
/// across the ellipsoid in that axis, as rounding the ray's direction by ε
/// already moves it; the cancellation of the thin axis's τ|D₃|² never
/// arises, as no product pairs D₃ with p₃. D × (p × D) is as accurate in
/// each component. Neither form divides: the test costs the cross product
/// instead of l's three products and differences.
///
/// Bounds, for a ray from the eye (the engine's camera rays) with
/// direction d:
/// - D = (scalesⱼ·(uⱼ·d))ⱼ is the exact frame's direction for a world
///   direction within 3.5·√3 ε of d (ε from each axis's rounding, 2 ε
///   from the dot product, 1 ε from the scale and the product).
/// - s = p·D and a = D·D within 3 ε of those of the rounded p and D; c
///   within ε/2 of the exact |p|² − 1; a − |p × D|² within a few ε of
///   the moved ray's; the roots q/a and c/q from q = s ± √(a − |p × D|²)
///   never cancel. So t is within a few ulps of the exact t of a ray
///   within a few ulps of d, with t's own conditioning (1/|cos θ| at
///   incidence θ) and no factor of the aspect or of the eye's distance.
/// - the hit or miss is that of a ray within a few ulps of d: only pixels
///   whose ray passes within that of the silhouette can differ.
/// - the normal is built from the hit's offset from the centre in this
///   frame, P = −l ∓ √(a − |p × D|²)·D/a (the sign from which root was
///   hit, as `SphereIntersection.stableNormal` takes it), and brought to
///   the world as Σⱼ scalesⱼ·Pⱼ·uⱼ (the gradient of Σⱼ (uⱼ·(X − C)/Aⱼ)²):
///   each term relative to the largest within a few ulps, so the normal is
///   within a few ulps of the exact normal's direction at the hit of a ray
///   within a few ulps of d, and never reversed away from the rim.
extension EllipsoidFrame {
  /// D, the ray's direction in the unit sphere's frame, times 2⁻ᵏ.
  @inlinable @inline(__always)
  package func localDirection(_ d: Vector3<S>) -> Vector3<S> {
    Vector3(
      scales.x * axis0.dot(d), scales.y * axis1.dot(d),
      scales.z * axis2.dot(d))
  }

  /// The nearest root in (tMin, tMax), tMin ≥ 0, of the ray from the eye
  /// with direction `d`, in the world's t, or nil.
  ///
  /// The flat searches meet ellipsoids behind the eye too: with the eye
  /// outside (c > 0) and the centre behind (s < 0) both roots are
  /// negative, and the ray is rejected first, as `StableKernel` rejects
  /// such spheres.
  @inlinable @inline(__always)
  package func root(
    direction d: Vector3<S>, after tMin: S = 0, before tMax: S
  ) -> S? {
    let direction = localDirection(d)
    let s = offset.dot(direction)
    if c > 0 && s < 0 { return nil }
    let a = direction.lengthSquared
    let ac = a * c
    let sSquared = s * s
    // As `SphereIntersection.stableRoot`, with r = 1: s² − ac where it
    // loses at most a bit (the eye inside or near the surface), else
    // a − |p × D|², after the same early rejection of clear misses (both
    // forms within a few ε·a·|p|² of the truth, |p|² = c + 1).
    let quarterDiscriminant: S
    if !(ac > sSquared * 0.5) {
      quarterDiscriminant = sSquared - ac
    } else {
      let margin = 32 * S.ulpOfOne * a * (c + 1)
      if sSquared - ac < -margin { return nil }
      quarterDiscriminant = a - offset.cross(direction).lengthSquared
    }
    guard quarterDiscriminant >= 0 else { return nil }
    let root = quarterDiscriminant.squareRoot()
    let q = s >= 0 ? s + root : s - root
    let viaQuotient = c / q
    let viaScale = q / a
    // In order even where a tangent rounds the two forms out of it, so
    // that the answer does not depend on tMax (`ObjectSpaceEllipsoid`).
    let near = Swift.min(viaQuotient, viaScale)
    let far = Swift.max(viaQuotient, viaScale)
    let (lower, upper) = (tMin * inverseTScale, tMax * inverseTScale)
    if near > lower && near < upper { return near * tScale }
    if far > lower && far < upper { return far * tScale }
    return nil
  }

  /// The outward unit normal in the world at the root t (`root`) of the
  /// camera ray with direction `d`.
  ///
  /// For an eye closer than 64 radii of the unit sphere (c < 4095) the
  /// hit's offset t̂·D − p is used directly, as for spheres
  /// (`SphereIntersection.stableNormal`); farther, where it would cancel,
  /// −l ∓ √(a − |p × D|²)·D/a with l = (D × (p × D))/a.
  @inlinable
  package func normal(direction d: Vector3<S>, t: S) -> Vector3<S> {
    let direction = localDirection(d)
    let offsetFromCenter: Vector3<S>
    if c < 4095 {
      offsetFromCenter = direction * (t * inverseTScale) - offset
    } else {
      let inverseA = 1 / direction.lengthSquared
      let across = offset.cross(direction)
      let l = direction.cross(across) * inverseA
      let quarterDiscriminant = Swift.max(
        direction.lengthSquared - across.lengthSquared, 0)
      // Camera rays start at t = 0: the smaller root is the one hit
      // exactly when the eye is outside (c > 0).
      let along = quarterDiscriminant.squareRoot() * inverseA
      offsetFromCenter = direction * (c > 0 ? -along : along) - l
    }
    let world =
      axis0 * (scales.x * offsetFromCenter.x)
      + axis1 * (scales.y * offsetFromCenter.y)
      + axis2 * (scales.z * offsetFromCenter.z)
    return world.normalizedByReciprocal()
  }
}
