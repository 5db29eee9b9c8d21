import ExactArithmetic
import Geometry
import SceneDescription

/// An ellipsoid as a camera ray's test sees it: in the frame of its axes
/// (`EllipsoidAxes`), each divided by its semi-axis, where it is the unit
/// sphere, with the centre given relative to the eye. The constants are
/// computed once per ellipsoid in DoubleDouble and rounded once to S;
/// per ray there remain the local direction and the stable quadratic
/// (`EllipsoidFrame+Intersection.swift`).
///
/// A camera ray E + t·d is, in this frame, −p + t·D with
/// p = (uⱼ·(C − E)/Aⱼ)ⱼ and D = (uⱼ·d/Aⱼ)ⱼ. D is stored scaled by 2⁻ᵏ, the
/// power of two that brings its largest factor 1/A_min into [1, 2), so that
/// a = |D|² stays near 1 at any aspect and the test's products stay in
/// range; the test's t̂ is t·2ᵏ, and t = t̂·2⁻ᵏ exactly.
///
/// Why p is computed from the axes in DoubleDouble rather than rounded:
/// the local direction uses the axes rounded to S, which is the exact
/// frame applied to a direction within ε of d (a rotation by ε), so the
/// test is exact for a ray within a few ulps of the one given. Rounding
/// the axes for p as well would turn the whole ellipsoid by ε about its
/// centre, moving the surface by ε·|C − E| where the eye may be far closer
/// to it than to its centre (a disc seen from just above its edge).
@usableFromInline
package struct EllipsoidFrame<S: RayScalar>: Sendable {
  /// u₀, u₁, u₂, the world's unit axes, rounded to S.
  @usableFromInline
  package var axis0: Vector3<S>
  @usableFromInline
  package var axis1: Vector3<S>
  @usableFromInline
  package var axis2: Vector3<S>
  /// 2⁻ᵏ/Aⱼ: the local direction is (scalesⱼ·(uⱼ·d))ⱼ. The largest is
  /// in [1, 2).
  @usableFromInline
  package var scales: Vector3<S>
  /// p = (uⱼ·(C − E)/Aⱼ)ⱼ, the centre relative to the eye in the unit
  /// sphere's frame, each component rounded once from DoubleDouble.
  @usableFromInline
  package var offset: Vector3<S>
  /// |p|² − 1 from p in DoubleDouble (before its rounding), rounded once:
  /// positive when the eye is outside.
  @usableFromInline
  package var c: S
  /// 2⁻ᵏ and 2ᵏ: t = t̂·2⁻ᵏ between the test's t̂ and the world's t.
  @usableFromInline
  package var tScale: S
  @usableFromInline
  package var inverseTScale: S

  /// The frame of `ellipsoid` seen from `eye`; one that never reports a
  /// hit (`never`) when its axes or its constants do not fit S's range
  /// with the margin the test's products need (|p|² below S's largest
  /// finite value over 64): an ellipsoid too thin beside its distance from
  /// the eye, which `LengthScale` keeps from the render.
  @usableFromInline
  package init(_ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>) {
    guard
      let axes = EllipsoidAxes(
        matrix: ellipsoid.matrix, sphere: ellipsoid.sphere),
      let frame = Self(axes, eye: eye)
    else {
      self = .never
      return
    }
    self = frame
  }

  /// The frame of the ellipsoid with axes `axes` seen from `eye`, or nil
  /// when it does not fit S (see `init(_:eye:)`).
  @usableFromInline
  package init?(_ axes: EllipsoidAxes, eye: Vector3<Double>) {
    typealias DD = DoubleDouble
    func rounded(_ x: DD) -> S { CameraRelative.narrowed(x.hi, x.lo) }
    let shortest = axes.lengths.min() ?? 0
    guard shortest > 0, shortest.isFinite else { return nil }
    let k = (1 / shortest).exponent
    let down = EllipsoidAxes.power(-k)
    let up = EllipsoidAxes.power(k)
    guard down > 0, up.isFinite else { return nil }
    let relative = axes.center - Vector3<DD>(eye)
    let p = (0..<3).map { j in
      axes.directions[j].dot(relative) / axes.lengths[j]
    }
    let scales = axes.lengths.map { rounded(1 / $0 * down) }
    let cExact = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1
    let limit = DD(S.greatestFiniteMagnitude) / 64
    guard cExact.isFinite, cExact + 1 < limit,
      scales.allSatisfy({ $0.isNormal }), rounded(down).isNormal,
      rounded(up).isNormal
    else { return nil }
    let axis = axes.directions.map { direction in
      Vector3(rounded(direction.x), rounded(direction.y), rounded(direction.z))
    }
    (axis0, axis1, axis2) = (axis[0], axis[1], axis[2])
    self.scales = Vector3(scales[0], scales[1], scales[2])
    offset = Vector3(rounded(p[0]), rounded(p[1]), rounded(p[2]))
    c = rounded(cExact)
    (tScale, inverseTScale) = (rounded(down), rounded(up))
  }

  init(
    axes: (Vector3<S>, Vector3<S>, Vector3<S>), scales: Vector3<S>,
    offset: Vector3<S>, c: S, tScale: S, inverseTScale: S
  ) {
    (axis0, axis1, axis2) = axes
    self.scales = scales
    self.offset = offset
    self.c = c
    self.tScale = tScale
    self.inverseTScale = inverseTScale
  }

  /// A frame no ray hits: its centre at the eye with c = 1 > 0 claims
  /// the eye outside a sphere it is at the centre of, so s = 0 and
  /// s² − ac = −a < 0 on every ray (the early rejection of `root`).
  @usableFromInline
  package static var never: EllipsoidFrame {
    EllipsoidFrame(
      axes: (Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)),
      scales: Vector3(1, 1, 1), offset: .zero, c: 1, tScale: 1,
      inverseTScale: 1)
  }
}
