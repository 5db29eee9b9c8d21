import Geometry
import SceneDescription
import PlatformSupport

/// Pixels from `firstColumn` to `lastColumn` and `firstRow` to `lastRow`,
/// ends included; empty when first > last.
struct PixelBox: Sendable, Equatable {
  var firstColumn: Int32
  var lastColumn: Int32
  var firstRow: Int32
  var lastRow: Int32

  static let empty = PixelBox(
    firstColumn: 0, lastColumn: -1, firstRow: 0, lastRow: -1)

  var isEmpty: Bool { firstColumn > lastColumn || firstRow > lastRow }
  /// Only for boxes that are not empty.
  var columns: ClosedRange<Int> { Int(firstColumn)...Int(lastColumn) }
  var rows: ClosedRange<Int> { Int(firstRow)...Int(lastRow) }
  var area: Int {
    Int(lastColumn - firstColumn + 1) * Int(lastRow - firstRow + 1)
  }
}

/// The pixels whose camera rays may come within a distance of a point.
struct ScreenProjection: Sendable {
  /// The last row of M⁻¹, M = [u, (H/W)·v, D·w]: rᵢ·d over r₃·d is d's
  /// screen x (i = 1) or y (i = 2), rows 1 and 2 being `axes`.
  let r3: Vector3<Double>
  /// Per camera rather than per sphere: |r₃|, |r₃|², and for each screen
  /// axis rᵢ, |rᵢ|, rᵢ·r₃ and |rᵢ × r₃|².
  let r3Length: Double
  let r3LengthSquared: Double
  let axes: (x: Axis, y: Axis)
  /// A bound on how much the computed rows and products can err, relative
  /// to their sizes: max|column of M|·max|rᵢ| ε-units become this slack.
  let condition: Double
  let width: Int
  let height: Int
  let screen: ScreenMap
  let whole: PixelBox

  struct Axis: Sendable {
    let row: Vector3<Double>
    let length: Double
    let dotR3: Double
    let crossR3Squared: Double
  }

  init(camera: PerspectiveCamera<Double>, screen: ScreenMap) {
    let (width, height) = (screen.width, screen.height)
    let aspect = Double(height) / Double(width)
    let (u, v, w) = (
      camera.horizontal, camera.up * aspect,
      camera.direction * camera.focalDistance
    )
    let determinant = u.dot(v.cross(w))
    let r1 = v.cross(w) / determinant
    let r2 = w.cross(u) / determinant
    r3 = u.cross(v) / determinant
    condition =
      Swift.max(u.length, v.length, w.length)
      * Swift.max(r1.length, r2.length, r3.length)
    r3Length = r3.length
    r3LengthSquared = r3.lengthSquared
    let r3 = r3
    func axis(_ row: Vector3<Double>) -> Axis {
      Axis(
        row: row, length: row.length, dotR3: row.dot(r3),
        crossR3Squared: row.cross(r3).lengthSquared)
    }
    axes = (axis(r1), axis(r2))
    self.width = width
    self.height = height
    self.screen = screen
    whole = PixelBox(
      firstColumn: 0, lastColumn: Int32(width - 1), firstRow: 0,
      lastRow: Int32(height - 1))
  }

  /// Where on the screen the rays that pass within a ball in front of the
  /// eye may lie.
  enum Extent {
    /// Wholly behind the plane through the eye parallel to the screen.
    case behind
    /// Near that plane, where the silhouette has no bounded box, or
    /// anything not finite.
    case unbounded
    /// Screen x and y intervals, padded for this arithmetic's rounding.
    case within(
      x: (lower: Double, upper: Double), y: (lower: Double, upper: Double))
  }

  /// The screen extent of the rays that may pass within `reach` of
  /// `center` (relative to the eye) in front of the eye.
  func extent(center p: Vector3<Double>, reach ρ: Double) -> Extent {
    let p3 = r3.dot(p)
    let n3 = r3Length
    // A hit point h = t·d has r₃·h > 0 and |h − p| ≤ ρ, so r₃·p > −ρ|r₃|.
    if p3 <= -ρ * n3 * (1 + 0x1p-20) { return .behind }
    // With r₃·p ≥ 2ρ|r₃| the ball is at most 30° wide seen from that
    // plane, A below stays within [3/4, 1]·(r₃·p)², and every quantity is
    // a sum of terms of known size (`Λ`).
    guard p3 >= 2 * ρ * n3, p3.isFinite, ρ.isFinite, p.isFinite else {
      return .unbounded
    }
    // Shared by both axes: A, 1/A, 1/P₃ and |p| + ρ (one division each
    // rather than one per axis; the extra rounding is far inside the pad).
    let shared = IntervalTerms(
      p3: p3, ρ: ρ, a: p3 * p3 - ρ * ρ * r3LengthSquared, extent: p.length + ρ)
    guard let x = screenInterval(axes.x, p, shared),
      let y = screenInterval(axes.y, p, shared)
    else { return .unbounded }
    return .within(x: x, y: y)
  }

  /// The pixels whose rays may pass within `reach` of `center` (relative
  /// to the eye) in front of the eye: every pixel when the ball comes
  /// near the plane through the eye parallel to the screen, where its
  /// silhouette has no bounded box, or when anything is not finite.
  ///
  /// - Parameter margin: pixels added on every side, for rays that leave
  ///   from a pixel's centre by up to that many pixels along each axis.
  func pixelBox(center p: Vector3<Double>, reach ρ: Double, margin: Double = 0)
    -> PixelBox
  {
    pixelBox(extent(center: p, reach: ρ), margin: margin)
  }

  /// The pixels whose rays may pass within `reach` of the triangle with
  /// corners `a`, `b` and `c` (relative to the eye). The points within ρ
  /// of a triangle are the convex hull of the balls of radius ρ about its
  /// corners, and seen from the eye, with all three balls in front, the
  /// hull's screen image is the hull of theirs: its box is the union of
  /// the balls' boxes. A ball behind or near the eye's plane gives every
  /// pixel, unless all three are behind.
  @inline(__always)
  func pixelBox(
    triangle a: Vector3<Double>, _ b: Vector3<Double>, _ c: Vector3<Double>,
    reach ρ: Double, margin: Double
  ) -> PixelBox {
    if let (x, y) = triangleExtent(a, b, c, reach: ρ) {
      return pixelBox(.within(x: x, y: y), margin: margin)
    }
    let extents = (
      cornerExtent(a, reach: ρ), cornerExtent(b, reach: ρ),
      cornerExtent(c, reach: ρ)
    )
    switch extents {
    case (.behind, .behind, .behind):
      return .empty
    case (
      .within(let x0, let y0), .within(let x1, let y1),
      .within(let x2, let y2)
    ):
      return pixelBox(
        .within(
          x: (
            Swift.min(x0.lower, x1.lower, x2.lower),
            Swift.max(x0.upper, x1.upper, x2.upper)
          ),
          y: (
            Swift.min(y0.lower, y1.lower, y2.lower),
            Swift.max(y0.upper, y1.upper, y2.upper)
          )),
        margin: margin)
    default:
      return whole
    }
  }

  /// `extent` for a ball whose radius is below a millionth of its
  /// distance from the eye's plane (a triangle's corner and its rounding):
  /// the centre's screen coordinates k = Pᵢ/P₃ and a bound on how far the
  /// ball's other points project from them, instead of the ellipse.
  ///
  /// For q = p + e with |e| ≤ ρ, (Pᵢ + rᵢ·e)/(P₃ + r₃·e) − Pᵢ/P₃ =
  /// (P₃ rᵢ·e − Pᵢ r₃·e)/(P₃(P₃ + r₃·e)), at most
  /// ρ(|rᵢ| + |k| |r₃|)/P₃ · 1/(1 − 2⁻²⁰) when ρ|r₃| ≤ 2⁻²⁰P₃; the result is
  /// padded as `screenInterval` pads its own (2⁻³⁰ of the scale of the
  /// terms, with ‖p‖₁ for |p|), far beyond the rounding of k. Otherwise
  /// `extent`.
  @inline(__always)
  func cornerExtent(_ p: Vector3<Double>, reach ρ: Double) -> Extent {
    let p3 = r3.dot(p)
    let far = p.x.magnitude + p.y.magnitude + p.z.magnitude + ρ
    guard p3 >= 0x1p20 * ρ * r3Length, far.isFinite, ρ.isFinite else {
      return extent(center: p, reach: ρ)
    }
    let inverseP3 = 1 / p3
    func interval(_ axis: Axis) -> (lower: Double, upper: Double)? {
      let pi = axis.row.dot(p)
      let k = pi * inverseP3
      let (reach, pad) = cornerSlack(
        axis, k: k.magnitude, pi: pi.magnitude, inverseP3: inverseP3,
        far: far, reach: ρ)
      let (lower, upper) = (k - reach - pad, k + reach + pad)
      guard lower.isFinite, upper.isFinite else { return nil }
      return (lower, upper)
    }
    guard let x = interval(axes.x), let y = interval(axes.y) else {
      return extent(center: p, reach: ρ)
    }
    return .within(x: x, y: y)
  }

  /// `cornerExtent`'s bound on one axis: how far the ball's points
  /// project from the centre's screen point (reach), and the pad for this
  /// arithmetic's rounding, from |k|, |Pᵢ|, 1/P₃ and far = ‖p‖₁ + ρ. Every
  /// operation is monotone in each of those, rounding included, which
  /// `triangleExtent` relies on when it passes the largest of three
  /// corners'.
  @inline(__always)
  private func cornerSlack(
    _ axis: Axis, k: Double, pi: Double, inverseP3: Double, far: Double,
    reach ρ: Double
  ) -> (reach: Double, pad: Double) {
    let reach =
      ρ * (axis.length + k * r3Length) * inverseP3 * (1 + 0x1p-19)
    let scale = (pi + far * (axis.length + r3Length)) * inverseP3
    return (reach, 0x1p-30 * condition * (1 + scale + scale * scale))
  }

  /// `pixelBox(triangle:…)`'s usual case, every corner far enough in
  /// front for `cornerExtent`'s short way: the corners' screen points k and
  /// one reach and one pad per axis for all three, `cornerSlack` of the
  /// largest |k|, |Pᵢ|, 1/P₃ and ‖p‖₁ + ρ of the corners (four divisions
  /// fewer, and a mesh of 10⁶ triangles has three million corners). That
  /// is monotone in each, so each interval holds the union of the three
  /// corners' own. Only for corners within a factor 2 of each other in
  /// depth (P₃), as a mesh's small triangles are: then the largest 1/P₃ is
  /// at most twice a corner's own, the shared reach and pad at most 16
  /// times the largest corner's (the pad grows with the square of its
  /// scale), and all of it a few billionths of the image for such
  /// triangles. Nil, for the way by corners, otherwise: where a corner is
  /// not far in front, the corners' depths differ more, or anything is not
  /// finite.
  @inline(__always)
  func triangleExtent(
    _ a: Vector3<Double>, _ b: Vector3<Double>, _ c: Vector3<Double>,
    reach ρ: Double
  ) -> (x: (lower: Double, upper: Double), y: (lower: Double, upper: Double))? {
    let p3 = (r3.dot(a), r3.dot(b), r3.dot(c))
    func size(_ p: Vector3<Double>) -> Double {
      p.x.magnitude + p.y.magnitude + p.z.magnitude
    }
    let sizes = (size(a), size(b), size(c))
    let far = Swift.max(sizes.0, sizes.1, sizes.2) + ρ
    // Sums, as min and max may pass over a NaN.
    guard (sizes.0 + sizes.1 + sizes.2 + ρ).isFinite,
      (p3.0 + p3.1 + p3.2).isFinite,
      Swift.min(p3.0, p3.1, p3.2) >= 0x1p20 * ρ * r3Length,
      Swift.max(p3.0, p3.1, p3.2) <= 2 * Swift.min(p3.0, p3.1, p3.2)
    else { return nil }
    let inverse = (1 / p3.0, 1 / p3.1, 1 / p3.2)
    let largestInverse = Swift.max(inverse.0, inverse.1, inverse.2)
    func interval(_ axis: Axis) -> (lower: Double, upper: Double)? {
      let pi = (axis.row.dot(a), axis.row.dot(b), axis.row.dot(c))
      guard (pi.0 + pi.1 + pi.2).isFinite else { return nil }
      let k = (pi.0 * inverse.0, pi.1 * inverse.1, pi.2 * inverse.2)
      let (reach, pad) = cornerSlack(
        axis, k: Swift.max(k.0.magnitude, k.1.magnitude, k.2.magnitude),
        pi: Swift.max(pi.0.magnitude, pi.1.magnitude, pi.2.magnitude),
        inverseP3: largestInverse, far: far, reach: ρ)
      let lower = Swift.min(k.0, k.1, k.2) - reach - pad
      let upper = Swift.max(k.0, k.1, k.2) + reach + pad
      guard lower.isFinite, upper.isFinite else { return nil }
      return (lower, upper)
    }
    guard let x = interval(axes.x), let y = interval(axes.y) else {
      return nil
    }
    return (x, y)
  }

  /// The pixels of an extent: none behind the eye, every one when
  /// unbounded, else those whose own screen coordinates lie in the
  /// intervals, widened by `margin` pixels. Inlined into the triangles'
  /// boxes: meshes of 10⁶ and 5·10⁶ triangles 2–8 % faster on one thread.
  @inline(__always)
  func pixelBox(_ extent: Extent, margin: Double) -> PixelBox {
    let (x, y): ((lower: Double, upper: Double), (lower: Double, upper: Double))
    switch extent {
    case .behind: return .empty
    case .unbounded: return whole
    case .within(let xInterval, let yInterval): (x, y) = (xInterval, yInterval)
    }
    // The pixels whose own screen coordinates lie in the intervals. Those
    // were rounded in the render's precision (`screenX`: a division and a
    // subtraction, within 2 ε of the exact value on [−1, 1]); 4 ε of the
    // widest precision a render takes (Float), times the pixels per
    // screen unit, covers that with room for this Double arithmetic.
    let columns = (screen.column(x: x.lower), screen.column(x: x.upper))
    let rows = (screen.row(y: y.upper), screen.row(y: y.lower))
    let padColumns =
      4 * Double(Float.ulpOfOne) * Double(width) + 0x1p-30 + margin
    let padRows = 4 * Double(Float.ulpOfOne) * Double(height) + 0x1p-30 + margin
    func clamped(_ value: Double, _ limit: Int) -> Int32 {
      Int32(Swift.min(Swift.max(value, -1), Double(limit)))
    }
    func up(_ value: Double, _ limit: Int) -> Int32 {
      clamped(value.rounded(.up), limit)
    }
    func down(_ value: Double, _ limit: Int) -> Int32 {
      clamped(value.rounded(.down), limit)
    }
    let box = PixelBox(
      firstColumn: Swift.max(0, up(columns.0 - padColumns, width)),
      lastColumn: Swift.min(
        Int32(width - 1), down(columns.1 + padColumns, width)),
      firstRow: Swift.max(0, up(rows.0 - padRows, height)),
      lastRow: Swift.min(Int32(height - 1), down(rows.1 + padRows, height)))
    return box.isEmpty ? .empty : box
  }

  /// The screen coordinates k = rᵢ·d / r₃·d of the directions d within the
  /// ball: the planes (rᵢ − k r₃)·d = 0 tangent to it, where
  /// (rᵢ·p − k r₃·p)² = ρ²|rᵢ − k r₃|², a quadratic A k² − 2B k + C = 0 with
  /// A = P₃² − ρ²|r₃|², B = PᵢP₃ − ρ² rᵢ·r₃ and, by Lagrange's identity,
  /// B² − AC = ρ²(|P₃rᵢ − Pᵢr₃|² − ρ²|rᵢ × r₃|²): the P²ᵢP²₃ that cancel in
  /// the textbook discriminant never appear, so a sphere a billionth of
  /// its distance wide keeps its digits.
  ///
  /// Rounding: each quantity below is a sum of a few products of terms no
  /// larger than Λ·A (Λ defined below, in units of the screen), carrying
  /// at most a few dozen ε of Double each, and A ≥ 3/4·P₃² bounds the
  /// division. The interval is widened by 2⁻³⁰·Λ·condition, about 2²²
  /// times that bound; on screen that is a few billionths of the image.
  struct IntervalTerms {
    let p3: Double
    let ρ: Double
    let a: Double
    let inverseA: Double
    let inverseP3: Double
    let extent: Double

    init(p3: Double, ρ: Double, a: Double, extent: Double) {
      (self.p3, self.ρ, self.a, self.extent) = (p3, ρ, a, extent)
      inverseA = 1 / a
      inverseP3 = 1 / p3
    }
  }

  @inline(__always)
  private func screenInterval(
    _ axis: Axis, _ p: Vector3<Double>, _ terms: IntervalTerms
  ) -> (lower: Double, upper: Double)? {
    let (p3, ρ) = (terms.p3, terms.ρ)
    let ri = axis.row
    let pi = ri.dot(p)
    let b = pi * p3 - ρ * ρ * axis.dotR3
    let tangent = ri * p3 - r3 * pi
    let discriminant = Swift.max(
      0, tangent.lengthSquared - ρ * ρ * axis.crossR3Squared)
    let s = ρ * discriminant.squareRoot()
    let lower = (b - s) * terms.inverseA
    let upper = (b + s) * terms.inverseA
    // Λ: |Pᵢ|/P₃ is the centre's screen coordinate, |p|·|rᵢ|/P₃ bounds the
    // error of Pᵢ and P₃ in screen units, and ρ/P₃ times the rows the
    // ball's angular size.
    let scale =
      (pi.magnitude + terms.extent * (axis.length + r3Length)) * terms.inverseP3
    let pad = 0x1p-30 * condition * (1 + scale + scale * scale)
    guard lower.isFinite, upper.isFinite, pad.isFinite else { return nil }
    return (lower - pad, upper + pad)
  }
}
