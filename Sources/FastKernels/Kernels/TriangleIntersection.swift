import ExactArithmetic
import Geometry
import SceneDescription
import PlatformSupport

/// The watertight ray–triangle test of Woop, Benthin and Wald, "Watertight
/// Ray/Triangle Intersection", JCGT 2(1), 2013, shared by the package
/// `Triangle` and the render loop.
///
///     let prepared = WatertightRay(ray)          // once per ray
///     for triangle in candidates {               // cheap per triangle
///       if let hit = TriangleIntersection.intersect(
///         prepared, triangle.v0, triangle.v1, triangle.v2,
///         after: 0, before: nearest) { nearest = hit.t }
///     }
///
/// The ray is made the +z axis of a sheared frame (origin at the ray's
/// origin, direction (0, 0, 1)), where the question becomes whether the
/// origin lies in the triangle's 2D projection: the signs of three edge
/// functions. Two triangles sharing an edge compute that edge's function
/// from the same two transformed vertices, in opposite order, and
/// fl(a·b − c·d) = −fl(c·d − a·b) exactly; a nonzero result always has the
/// true sign (rounding is monotonic, so fl(a·b) and fl(c·d) never swap
/// order), and a zero is recomputed exactly. So a ray through a shared edge
/// or vertex is never outside both triangles: meshes do not leak. The test
/// is watertight, not exact: the shear itself rounds, so a ray a few ulps
/// beside an edge may hit either neighbour, but never neither.
///
/// Conventions:
/// - two-sided: either winding is hit;
/// - a ray through an edge or a vertex hits (edge functions of 0 count as
///   inside), so both neighbours may report it, at the same t up to rounding;
/// - only t in the open interval (tMin, tMax) counts;
/// - a triangle whose projection has zero area as computed (a repeated
///   vertex, or collinear vertices whose projection stays exactly collinear)
///   misses, as does a ray in the triangle's plane when the computation is
///   exact; a ray parallel to the plane but off it misses. `Triangle` also
///   rejects hits on triangles whose geometric normal is zero, for collinear
///   vertices whose rounded projection is not exactly collinear.
@usableFromInline
package enum TriangleIntersection {
  /// The nearest-in-interval hit of the prepared ray with triangle
  /// (v0, v1, v2), or nil.
  ///
  /// - Returns: t, and the barycentric weights (u, v, w) of v0, v1 and v2
  ///   (each in [0, 1] up to rounding, summing to 1 up to rounding), so that
  ///   the hit point is u·v0 + v·v1 + w·v2 and an interpolated normal is
  ///   u·n0 + v·n1 + w·n2.
  /// - Error: t is within a few ulps of the exact intersection of the ray
  ///   with the triangle's plane when the ray meets the triangle at a
  ///   reasonable angle (away from grazing): the z values of the vertices
  ///   are weighted by non-negative barycentrics, so nothing cancels (see
  ///   TriangleMethodTests for the measured bound). The barycentrics carry an
  ///   absolute error of a few ε times (distance from the origin / size of
  ///   the triangle): the shear subtracts nearly equal numbers.
  @inlinable
  package static func intersect<S: RayScalar>(
    _ ray: WatertightRay<S>, _ v0: Vector3<S>, _ v1: Vector3<S>,
    _ v2: Vector3<S>, after tMin: S, before tMax: S
  ) -> (t: S, u: S, v: S, w: S)? {
    intersect(
      ray, PermutedTriangle(ray, v0, v1, v2), after: tMin, before: tMax)
  }

  /// `intersect` for a triangle already carried into the ray's permuted
  /// frame, the same arithmetic and so the same bits: a triangle tested
  /// against many rays that share origin and permutation (a screen tile's)
  /// is permuted once for all of them.
  @inlinable @inline(__always)
  package static func intersect<S: RayScalar>(
    _ ray: WatertightRay<S>, _ triangle: PermutedTriangle<S>,
    after tMin: S, before tMax: S
  ) -> (t: S, u: S, v: S, w: S)? {
    intersect(ray, triangle, after: tMin, before: tMax) { nil }
  }

  /// `intersect` for a triangle whose t comes from its exact plane
  /// (`TrianglePlane.Exact`, for large and thin triangles): the same edge
  /// functions decide hit or miss on the ray's whole line and give the
  /// same barycentrics, bit for bit; t is the plane's, in (tMin, tMax).
  @inlinable @inline(__always)
  package static func intersect<S: RayScalar>(
    _ ray: WatertightRay<S>, _ triangle: PermutedTriangle<S>,
    plane: TrianglePlane.Exact<S>, after tMin: S, before tMax: S
  ) -> (t: S, u: S, v: S, w: S)? {
    intersect(ray, triangle, after: tMin, before: tMax) { plane }
  }

  /// `intersect` with t from the plane `exactPlane` gives, asked only once
  /// the edge functions say the ray's line meets the triangle (so a search
  /// looks up a triangle's plane for the few rays that reach it), or the
  /// watertight test's t when it gives none.
  @inlinable @inline(__always)
  package static func intersect<S: RayScalar>(
    _ ray: WatertightRay<S>, _ triangle: PermutedTriangle<S>,
    after tMin: S, before tMax: S,
    exactPlane: () -> TrianglePlane.Exact<S>?
  ) -> (t: S, u: S, v: S, w: S)? {
    guard let edges = edgeFunctions(ray, triangle) else { return nil }
    let (u, v, w) = (edges.u, edges.v, edges.w)
    let determinant = u + v + w
    guard determinant != 0 else { return nil }
    let t: S
    if let plane = exactPlane() {
      guard
        let planeT = plane.t(
          direction: ray.direction, after: tMin, before: tMax)
      else { return nil }
      t = planeT
    } else {
      let scaledT =
        u * (ray.shearZ * edges.az) + v * (ray.shearZ * edges.bz)
        + w * (ray.shearZ * edges.cz)
      t = scaledT / determinant
      guard t > tMin && t < tMax else { return nil }
    }
    let inverse = 1 / determinant
    return (t, u * inverse, v * inverse, w * inverse)
  }

  /// Whether the ray's line passes through the triangle as `intersect`
  /// decides it, without t: the edge functions agree in sign and their sum
  /// is not zero. The same answer as `intersect(…, after: −∞, before: ∞)`
  /// wherever that t cannot overflow or be NaN (for finite vertices and
  /// direction, once the products of the test stay finite); the fast
  /// engine's large triangles, which take t from their plane, use it where
  /// that holds (`LargeTrianglePlane.edgesDecide`).
  @inlinable @inline(__always)
  package static func covers<S: RayScalar>(
    _ ray: WatertightRay<S>, _ v0: Vector3<S>, _ v1: Vector3<S>,
    _ v2: Vector3<S>
  ) -> Bool {
    guard let edges = edgeFunctions(ray, PermutedTriangle(ray, v0, v1, v2))
    else { return false }
    return edges.u + edges.v + edges.w != 0
  }

  /// The edge functions u, v, w of the vertices sheared into the ray's
  /// frame and the vertices' z there, or nil when the signs of u, v, w
  /// disagree (the ray passes outside).
  @inlinable @inline(__always)
  static func edgeFunctions<S: RayScalar>(
    _ ray: WatertightRay<S>, _ triangle: PermutedTriangle<S>
  ) -> (u: S, v: S, w: S, az: S, bz: S, cz: S)? {
    let (a, b, c) = (triangle.a, triangle.b, triangle.c)
    let (az, bz, cz) = (a.z, b.z, c.z)
    // Shear so that the direction becomes (0, 0, 1/Sz): each vertex's
    // projection is a function of that vertex alone, identical for every
    // triangle sharing it.
    let ax = a.x - ray.shearX * az
    let ay = a.y - ray.shearY * az
    let bx = b.x - ray.shearX * bz
    let by = b.y - ray.shearY * bz
    let cx = c.x - ray.shearX * cz
    let cy = c.y - ray.shearY * cz
    // Edge functions: u of edge v1→v2, v of v2→v0, w of v0→v1.
    var u = cx * by - cy * bx
    var v = ax * cy - ay * cx
    var w = bx * ay - by * ax
    if u == 0 || v == 0 || w == 0 {
      (u, v, w) = exactEdgeFunctions(ax, ay, bx, by, cx, cy)
    }
    // Inside (or on the boundary) when no two signs disagree; NaNs (a zero
    // or non-finite direction) pass here and fail the t test.
    if (u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0) { return nil }
    return (u, v, w, az, bz, cz)
  }

  /// The three edge functions with each product exact, for when one of them
  /// rounded to 0 and its sign must be decided: in Double for Float inputs
  /// (24-bit products are exact in 53 bits), otherwise from `twoProduct`'s
  /// exact error terms (fl(a·b) = fl(c·d) whenever fl(a·b − c·d) = 0, and
  /// then a·b − c·d is exactly e_ab − e_cd, rounded once). Both keep
  /// f(q, p) = −f(p, q) exactly, so shared edges still agree.
  ///
  /// Exact unless the products are near the underflow threshold (sheared
  /// coordinates below about 10⁻¹⁴⁶ in Double), where FMA's error term is
  /// itself rounded; a Float result that is nonzero in Double but below
  /// Float's smallest subnormal keeps its sign as ±that subnormal.
  @inlinable @inline(never)
  static func exactEdgeFunctions<S: RayScalar>(
    _ ax: S, _ ay: S, _ bx: S, _ by: S, _ cx: S, _ cy: S
  ) -> (S, S, S) {
    if S.self == Float.self {
      func edge(_ p: S, _ q: S, _ r: S, _ s: S) -> S {
        let exact = Double(p) * Double(q) - Double(r) * Double(s)
        let narrowed = S(exact)
        if narrowed == 0 && exact != 0 {
          return exact > 0 ? S.leastNonzeroMagnitude : -S.leastNonzeroMagnitude
        }
        return narrowed
      }
      return (edge(cx, by, cy, bx), edge(ax, cy, ay, cx), edge(bx, ay, by, ax))
    }
    func edge(_ p: S, _ q: S, _ r: S, _ s: S) -> S {
      let first = Compensated.twoProduct(p, q)
      let second = Compensated.twoProduct(r, s)
      guard first.product == second.product else {
        return first.product - second.product
      }
      return first.error - second.error
    }
    return (edge(cx, by, cy, bx), edge(ax, cy, ay, cx), edge(bx, ay, by, ax))
  }
}

/// A triangle's vertices relative to a ray's origin, in the ray's permuted
/// frame (x, y, z = the ray's kx, ky, kz components): the first step of
/// the watertight test, before the shear. It depends on the ray only
/// through its origin and permutation, so rays that share both (a screen
/// tile's, as a rule) can share it.
@usableFromInline
package struct PermutedTriangle<S: RayScalar>: Sendable {
  @usableFromInline
  package var a: Vector3<S>
  @usableFromInline
  package var b: Vector3<S>
  @usableFromInline
  package var c: Vector3<S>

  @inlinable @inline(__always)
  package init(
    _ ray: WatertightRay<S>, _ v0: Vector3<S>, _ v1: Vector3<S>,
    _ v2: Vector3<S>
  ) {
    let a = v0 - ray.origin
    let b = v1 - ray.origin
    let c = v2 - ray.origin
    self.a = Vector3(a[ray.kx], a[ray.ky], a[ray.kz])
    self.b = Vector3(b[ray.kx], b[ray.ky], b[ray.kz])
    self.c = Vector3(c[ray.kx], c[ray.ky], c[ray.kz])
  }
}

extension WatertightRay {
  /// Whether `PermutedTriangle` gives the same vertices, bit for bit, for
  /// this ray as for `other`: the same permutation and the same origin,
  /// zeros' signs included (v − 0 and v − (−0) differ for v = −0).
  @inlinable @inline(__always)
  package func sharesFrame(with other: WatertightRay) -> Bool {
    func same(_ p: S, _ q: S) -> Bool { p == q && p.sign == q.sign }
    return kx == other.kx && ky == other.ky && kz == other.kz
      && same(origin.x, other.origin.x) && same(origin.y, other.origin.y)
      && same(origin.z, other.origin.z)
  }
}

/// A ray prepared for `TriangleIntersection`: the axis kz along which its
/// direction is largest becomes the sheared frame's z, and the shear that
/// turns the direction into (0, 0, 1) is computed once, so that each
/// triangle costs three subtractions, six multiply-adds and three 2×2
/// determinants before its first rejection.
///
/// kx and ky are the other two axes in cyclic order, swapped when the
/// direction's kz component is negative so that the projection keeps the
/// triangles' winding (the sign of the edge functions) as seen from the
/// ray. A zero or non-finite direction gives NaN shears, and every
/// triangle misses.
@usableFromInline
package struct WatertightRay<S: RayScalar>: Hashable, Sendable {
  @usableFromInline
  package var origin: Vector3<S>
  /// The ray's direction, for the plane of large triangles
  /// (`TrianglePlane`).
  @usableFromInline
  package var direction: Vector3<S>
  @usableFromInline
  package var kx: Int
  @usableFromInline
  package var ky: Int
  @usableFromInline
  package var kz: Int
  /// d[kx]/d[kz], d[ky]/d[kz] and 1/d[kz].
  @usableFromInline
  package var shearX: S
  @usableFromInline
  package var shearY: S
  @usableFromInline
  package var shearZ: S

  @inlinable
  package init(_ ray: Ray<S>) {
    let d = ray.direction
    let x = d.x.magnitude
    let y = d.y.magnitude
    let z = d.z.magnitude
    let kz = x >= y ? (x >= z ? 0 : 2) : (y >= z ? 1 : 2)
    var kx = kz == 2 ? 0 : kz + 1
    var ky = kx == 2 ? 0 : kx + 1
    if d[kz] < 0 { swap(&kx, &ky) }
    origin = ray.origin
    direction = d
    self.kx = kx
    self.ky = ky
    self.kz = kz
    shearX = d[kx] / d[kz]
    shearY = d[ky] / d[kz]
    shearZ = 1 / d[kz]
  }
}
