/// A camera ray's test of an ellipsoid in its unit-sphere frame
/// (`EllipsoidFrame`): the stable quadratic of `SphereIntersection`, with
/// the closest approach's cancellation taken out.
///
/// In this frame a flat ellipsoid is a unit sphere seen from far away
/// along a direction D that is nearly its thin axis: a disc of aspect 10⁸
/// seen from 2 radii puts the eye 2·10⁸ radii from the sphere. There the
/// closest approach l = p − (s/a)·D, computed component by component,
/// loses ε·|p| in every component to the cancellation of p against
/// (s/a)·D, which is 12 radii in Float: the hit is lost or the normal
/// reversed, though the ray, perturbed by ε in the world, moves l by only
/// ε·(distance travelled / the disc's radius). Here l's component along
/// D's largest coordinate is instead taken from l ⊥ D,
/// lₖ = −Σⱼ≠ₖ lⱼDⱼ / Dₖ, which does not cancel, and the others, whose
/// terms p and (s/a)·D are only as large as the ray's own travel across
/// the ellipsoid in that axis, lose ε of that, as the ray's rounding
/// already does. `l` is then within a few ulps of the closest approach of
/// the world ray moved by a few ulps, at every aspect and distance.
///
/// Bounds, for a ray from the eye (the engine's camera rays) with
/// direction d:
/// - D = (scalesⱼ·(uⱼ·d))ⱼ is the exact frame's direction for a world
///   direction within 3.5·√3 ε of d (ε from each axis's rounding, 2 ε
///   from the dot product, 1 ε from the scale and the product).
/// - s = p·D and a = D·D within 3 ε of those of the rounded p and D; c
///   within ε/2 of the exact |p|² − 1; the roots q/a and c/q from
///   q = s ± √(a·(1 − |l|²)) never cancel. So t is within a few ulps of the
///   exact t of a ray within a few ulps of d, with t's own conditioning
///   (1/|cos θ| at incidence θ) and no factor of the aspect or of the
///   eye's distance.
/// - the hit or miss is that of a ray within a few ulps of d: only pixels
///   whose ray passes within that of the silhouette can differ.
/// - the normal is built from the hit's offset from the centre in this
///   frame, P = −l ∓ √(1 − |l|²)·D/|D| (the sign from which root was hit,
///   as `SphereIntersection.stableNormal` takes it), and brought to the
///   world as Σⱼ scalesⱼ·Pⱼ·uⱼ (the gradient of Σⱼ (uⱼ·(X − C)/Aⱼ)²): each
///   term relative to the largest within a few ulps, so the normal is
///   within a few ulps of the exact normal's direction at the hit of a
///   ray within a few ulps of d, and never reversed away from the rim.
extension EllipsoidFrame {
  /// D, the ray's direction in the unit sphere's frame, times 2⁻ᵏ.
  @inlinable @inline(__always)
  public func localDirection(_ d: Vector3<S>) -> Vector3<S> {
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
  public func root(
    direction d: Vector3<S>, after tMin: S = 0, before tMax: S
  ) -> S? {
    let direction = localDirection(d)
    let s = offset.dot(direction)
    if c > 0 && s < 0 { return nil }
    let a = direction.lengthSquared
    let inverseA = 1 / a
    let ac = a * c
    let sSquared = s * s
    // As `SphereIntersection.stableRoot`, with r = 1: s² − ac where it
    // loses at most a bit (the eye inside or near the surface), else
    // a·(1 − |l|²), after the same early rejection of clear misses (both
    // forms within a few ε·a·|p|² of the truth, |p|² = c + 1).
    let quarterDiscriminant: S
    if !(ac > sSquared * 0.5) {
      quarterDiscriminant = sSquared - ac
    } else {
      let margin = 32 * S.ulpOfOne * a * (c + 1)
      if sSquared - ac < -margin { return nil }
      let l = Self.closestApproach(offset, direction, s * inverseA)
      quarterDiscriminant = a * (1 - l.lengthSquared)
    }
    guard quarterDiscriminant >= 0 else { return nil }
    let root = quarterDiscriminant.squareRoot()
    let q = s >= 0 ? s + root : s - root
    let viaQuotient = c / q
    let viaScale = q * inverseA
    let near = s >= 0 ? viaQuotient : viaScale
    let far = s >= 0 ? viaScale : viaQuotient
    let (lower, upper) = (tMin * inverseTScale, tMax * inverseTScale)
    if near > lower && near < upper { return near * tScale }
    if far > lower && far < upper { return far * tScale }
    return nil
  }

  /// The closest approach l = p − τ·D of the line t·D to the centre p
  /// (τ = s/a), its component along D's largest coordinate from l ⊥ D
  /// (see the type's notes).
  @inlinable @inline(__always)
  static func closestApproach(
    _ p: Vector3<S>, _ direction: Vector3<S>, _ tau: S
  ) -> Vector3<S> {
    var l = p - direction * tau
    let magnitude = (
      direction.x.magnitude, direction.y.magnitude, direction.z.magnitude
    )
    if magnitude.0 >= magnitude.1 && magnitude.0 >= magnitude.2 {
      l.x = -(l.y * direction.y + l.z * direction.z) / direction.x
    } else if magnitude.1 >= magnitude.2 {
      l.y = -(l.x * direction.x + l.z * direction.z) / direction.y
    } else {
      l.z = -(l.x * direction.x + l.y * direction.y) / direction.z
    }
    return l
  }

  /// The outward unit normal in the world at the root t (`root`) of the
  /// camera ray with direction `d`.
  ///
  /// For an eye closer than 64 radii of the unit sphere (c < 4095) the
  /// hit's offset t̂·D − p is used directly, as for spheres
  /// (`SphereIntersection.stableNormal`); farther, −l ∓ √(1 − |l|²)·D/|D|
  /// with l from `closestApproach`, where t̂·D − p would cancel.
  @inlinable
  public func normal(direction d: Vector3<S>, t: S) -> Vector3<S> {
    let direction = localDirection(d)
    let offsetFromCenter: Vector3<S>
    if c < 4095 {
      offsetFromCenter = direction * (t * inverseTScale) - offset
    } else {
      let a = direction.lengthSquared
      let inverseA = 1 / a
      let l = Self.closestApproach(
        offset, direction, offset.dot(direction) * inverseA)
      let gap = Swift.max(1 - l.lengthSquared, 0)
      // Camera rays start at t = 0: the smaller root is the one hit
      // exactly when the eye is outside (c > 0).
      let along = (a * gap).squareRoot() * inverseA
      offsetFromCenter = direction * (c > 0 ? -along : along) - l
    }
    let world =
      axis0 * (scales.x * offsetFromCenter.x)
      + axis1 * (scales.y * offsetFromCenter.y)
      + axis2 * (scales.z * offsetFromCenter.z)
    return world.normalized()
  }
}
