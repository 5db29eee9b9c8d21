import Geometry
import SceneDescription

/// The two ways of solving |o + t·d − centre|² = r² for t, shared by the
/// package `Sphere` and the render loop.
///
/// Both return the nearest root in the open interval (tMin, tMax), so a ray
/// starting inside the sphere (or on it, with tMin = 0) hits the far side.
@usableFromInline
package enum SphereIntersection {
  /// The course's textbook formula, kept for comparison and for the course's
  /// images: a = d·d, b = 2f·d, c = f·f − r² with f = o − centre,
  /// t = (−b ∓ √(b² − 4ac)) / 2a.
  ///
  /// It fails in three known ways: b² − 4ac cancels for a small far sphere
  /// (every digit lost once L/r ≳ ε^(−1/2)); −b + √Δ cancels for the far root;
  /// and c = |f|² − r² cancels for a huge sphere seen from close by.
  @inlinable @inline(__always)
  package static func naiveRoot<S: RayScalar>(
    origin: Vector3<S>, direction: Vector3<S>,
    center: Vector3<S>, radius: S, after tMin: S, before tMax: S
  ) -> S? {
    let f = origin - center
    let a = direction.dot(direction)
    let b = 2 * f.dot(direction)
    let c = f.dot(f) - radius * radius
    let discriminant = b * b - 4 * a * c
    guard discriminant >= 0 else { return nil }
    let root = discriminant.squareRoot()
    let near = (-b - root) / (2 * a)
    if near > tMin && near < tMax { return near }
    let far = (-b + root) / (2 * a)
    if far > tMin && far < tMax { return far }
    return nil
  }

  /// The cancellation-free solution, with the sphere given relative to the
  /// ray's origin: `offset` p = centre − origin and `c` = |p|² − r² (computed
  /// accurately by `CameraRelative.sphere` or `Sphere.relative(to:)`).
  ///
  /// With s = p·d, the discriminant is taken as a·(r² − |l|²), where
  /// l = p − (s/a)·d is the centre's offset from the ray's line (pbrt-v4;
  /// Haines et al., Ray Tracing Gems ch. 7): l is computed component-wise
  /// without cancelling, where s² − ac loses everything for a small far
  /// sphere. The roots are q/a and c/q with q = s + sign(s)·√Δ, so no root is
  /// found by subtracting nearly equal numbers.
  ///
  /// - Returns: the nearest root in (tMin, tMax) and whether it is the
  ///   smaller root, where the ray enters the sphere; nil on a miss,
  ///   including a tangent ray whose double root lies outside the interval.
  @inlinable @inline(__always)
  package static func stableRoot<S: RayScalar>(
    direction d: Vector3<S>, lengthSquared a: S,
    inverseLengthSquared inverseA: S,
    offset p: Vector3<S>, c: S, radiusSquared: S,
    after tMin: S, before tMax: S
  ) -> (t: S, entering: Bool)? {
    var approach: ClosestApproach<S>?
    return stableRoot(
      direction: d, lengthSquared: a, inverseLengthSquared: inverseA,
      offset: p, c: c, radiusSquared: radiusSquared, after: tMin,
      before: tMax, approach: &approach)
  }

  /// The centre's offset l from the ray's line and √Δ/2 = √(a·(r² − |l|²)),
  /// as `stableRoot` computes them on its way to a root of a sphere whose
  /// discriminant cancels (a small far one): the normal's far form
  /// (`stableNormal`) needs exactly these values again.
  @usableFromInline
  package struct ClosestApproach<S: RayScalar>: Sendable {
    @usableFromInline
    package var offset: Vector3<S>
    @usableFromInline
    package var root: S

    @inlinable
    package init(offset: Vector3<S>, root: S) {
      self.offset = offset
      self.root = root
    }
  }

  /// `stableRoot`, also setting `approach` to the closest-approach values
  /// when it computed them (the cancelling case) and to nil otherwise, on
  /// a hit; on a miss `approach` is unspecified.
  @inlinable @inline(__always)
  package static func stableRoot<S: RayScalar>(
    direction d: Vector3<S>, lengthSquared a: S,
    inverseLengthSquared inverseA: S,
    offset p: Vector3<S>, c: S, radiusSquared: S,
    after tMin: S, before tMax: S, approach: inout ClosestApproach<S>?
  ) -> (t: S, entering: Bool)? {
    let s = p.dot(d)
    let ac = a * c
    let sSquared = s * s
    // Δ/4 = s² − ac. Where ac ≤ s²/2 the subtraction loses at most one bit
    // and s and c are both accurate (c from `CameraRelative`), so this form
    // is the accurate one: it holds for the eye inside a sphere (c < 0) and
    // for huge spheres seen from close by, where the closest-approach form
    // below would lose ε·|p|² against a discriminant of order s² (measured:
    // 2,600 ε on a planet of radius 10⁹ against 1 ε here). Otherwise s² and
    // ac nearly cancel, as for a small far sphere, and a·(r² − |l|²) is the
    // accurate form.
    let quarterDiscriminant: S
    var l = Vector3<S>.zero
    let cancels = ac > sSquared * 0.5
    if !cancels {
      quarterDiscriminant = sSquared - ac
    } else {
      // Most rays miss most spheres, and a clear miss needs no accurate
      // discriminant: both forms are within a few ε·a·|p|² of the truth
      // (|p|² = c + r²), so below −32 ε·a·|p|² both are negative and the
      // answer is the same as the careful form's, for a quarter of its cost.
      let margin = 32 * S.ulpOfOne * a * (c + radiusSquared)
      if sSquared - ac < -margin { return nil }
      l = p - d * (s * inverseA)
      quarterDiscriminant = a * (radiusSquared - l.lengthSquared)
    }
    guard quarterDiscriminant >= 0 else { return nil }
    let root = quarterDiscriminant.squareRoot()
    approach = cancels ? ClosestApproach(offset: l, root: root) : nil
    let q = s >= 0 ? s + root : s - root
    let viaQuotient = c / q
    let viaScale = q * inverseA
    let near = s >= 0 ? viaQuotient : viaScale
    if near > tMin && near < tMax { return (near, true) }
    let far = s >= 0 ? viaScale : viaQuotient
    if far > tMin && far < tMax { return (far, false) }
    return nil
  }

  /// The outward unit normal at the root t of `stableRoot`, from the centre's
  /// offset from the ray's line rather than from hit point − centre, which
  /// cancels for a small far sphere: hit − centre = ∓√((r² − |l|²)/a)·d − l,
  /// the sign from `entering`, with √((r² − |l|²)/a) taken as
  /// √(a·(r² − |l|²))/a from the root's own square root (the far form of
  /// `stableRoot` computes it), which saves a square root on every far hit:
  /// within 3 ε of the direct form (1.75 ε against 1 ε, from their
  /// roundings), far below l's own error there. Which root was hit is
  /// passed in rather than found by comparing t with s/a: for a sphere 10⁸
  /// radii away in Float the two roots round to the same t, and the
  /// comparison would flip the normal.
  ///
  /// The vector has length r in exact arithmetic, so it is scaled by 1/r and
  /// its length corrected by one Newton step for 1/√(n·n), whose error is
  /// about (3/8)·(n·n − 1)²: below ε once |n·n − 1| < √ε, which holds but
  /// where l itself is inaccurate; there the full normalisation runs.
  /// This saves a square root and a division on every hit.
  @inlinable @inline(__always)
  package static func stableNormal<S: RayScalar>(
    direction d: Vector3<S>, lengthSquared a: S,
    inverseLengthSquared inverseA: S,
    offset p: Vector3<S>, radiusSquared: S, inverseRadius: S, entering: Bool
  ) -> Vector3<S> {
    let s = p.dot(d)
    let l = p - d * (s * inverseA)
    let gap = Swift.max(radiusSquared - l.lengthSquared, 0)
    return stableNormal(
      direction: d, inverseLengthSquared: inverseA,
      approach: ClosestApproach(offset: l, root: (a * gap).squareRoot()),
      inverseRadius: inverseRadius, entering: entering)
  }

  /// `stableNormal` from the closest-approach values `stableRoot` found
  /// (the same bits as computing them again).
  @inlinable @inline(__always)
  package static func stableNormal<S: RayScalar>(
    direction d: Vector3<S>, inverseLengthSquared inverseA: S,
    approach: ClosestApproach<S>, inverseRadius: S, entering: Bool
  ) -> Vector3<S> {
    let l = approach.offset
    // `magnitude`: a discriminant that underflowed to −0 gives the +0 of
    // the form above.
    let along = approach.root.magnitude * inverseA
    let side: S = entering ? -1 : 1
    let outward = d * (side * along) - l
    let scaled = outward * inverseRadius
    let lengthSquared = scaled.lengthSquared
    if (lengthSquared - 1).magnitude < S.ulpOfOne.squareRoot() {
      return scaled * (1.5 - 0.5 * lengthSquared)
    }
    return outward.normalizedByReciprocal()
  }

  /// The outward unit normal at a root of `stableRoot`, as every stable
  /// test takes it (the model's `Sphere` and the fast engine alike).
  ///
  /// For a sphere closer than 64 radii (c < 4095 r²) the hit point's
  /// offset t·d − p is used directly: t's relative error ε becomes at most
  /// 64 ε in the normal's direction, and it costs neither the
  /// closest-approach vector nor a square root. Farther spheres, where
  /// that offset cancels, take `stableNormal`: from `approach` when the
  /// search kept what `stableRoot` computed for this hit, which saves
  /// computing the same l and r² − |l|² a second time.
  @inlinable @inline(__always)
  package static func stableNormal<S: RayScalar>(
    direction d: Vector3<S>, lengthSquared a: S,
    inverseLengthSquared inverseA: S, t: S,
    offset p: Vector3<S>, c: S, radiusSquared: S, inverseRadius: S,
    entering: Bool, approach: ClosestApproach<S>? = nil
  ) -> Vector3<S> {
    if c < 4095 * radiusSquared {
      let scaled = (d * t - p) * inverseRadius
      let lengthSquared = scaled.lengthSquared
      if (lengthSquared - 1).magnitude < S.ulpOfOne.squareRoot() {
        return scaled * (1.5 - 0.5 * lengthSquared)
      }
    }
    if let approach {
      return stableNormal(
        direction: d, inverseLengthSquared: inverseA, approach: approach,
        inverseRadius: inverseRadius, entering: entering)
    }
    return stableNormal(
      direction: d, lengthSquared: a, inverseLengthSquared: inverseA,
      offset: p, radiusSquared: radiusSquared, inverseRadius: inverseRadius,
      entering: entering)
  }

  /// 1 / a for a = d·d, as every stable test takes it: a camera ray is unit
  /// to within a few ulps, and with a = 1 + δ, 2 − a is 1/a to within
  /// δ² < ε once |δ| < 2^−26, which saves a division per ray.
  @inlinable @inline(__always)
  package static func inverseLengthSquared<S: RayScalar>(_ a: S) -> S {
    let deviation = a - 1
    return deviation.magnitude < 0x1p-26 ? 1 - deviation : 1 / a
  }

  /// The course's normal: (o + t·d − centre), normalised.
  @inlinable
  package static func naiveNormal<S: RayScalar>(
    origin: Vector3<S>, direction: Vector3<S>, center: Vector3<S>, t: S
  ) -> Vector3<S> {
    (origin + direction * t - center).normalized()
  }
}
