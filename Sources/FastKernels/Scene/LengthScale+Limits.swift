import Geometry
import SceneDescription

/// The limits of rescaling: what no power of two can bring into the
/// render precision's range (see `LengthScale`).
extension LengthScale {
  /// Why `scene` cannot be drawn right in `precision`, or nil: an object
  /// so small beside its own lengths seen from the eye that, at the scale
  /// it is traced at (its largest such length brought near 1, `layers`),
  /// the squares and products of its test fall below the precision's
  /// normal range, where they keep few digits or none. A sphere whose
  /// radius squared does (a radius of 1e-25 three units from the eye in
  /// Float: (r/L)² = 10⁻⁵⁰); a triangle whose longest edge squared, times
  /// its reach from the eye where that is below 1, does (its edge functions
  /// and their sum weighted by depth, `TriangleIntersection`); an ellipsoid
  /// whose shortest axis squared does (its local ray's direction, M⁻¹·d,
  /// would overflow). A plane never does: its only length is its distance
  /// from the eye. Objects that fail only at the scene's common scale are
  /// traced at their own (`layers`); these fail at their own too, and the
  /// scene is refused rather than drawn wrong.
  ///
  /// Nothing here depends on where the eye is: every length is an offset
  /// from it, so an eye at 1e14 beside a unit sphere, or at 1e300 beside
  /// a speck of 1e-300 (double), is judged as the same scene with the eye
  /// at the origin (`frame` moves such scenes to the eye before scaling).
  ///
  /// What would hold the scene is `precision.remedy`. A large mesh or
  /// group is measured by up to `threads` threads, with the same result.
  @usableFromInline
  package static func problem(
    _ scene: Scene, precision: Precision, threads: Int = 1
  ) -> String? {
    let scale: (Double) -> Double = {
      switch precision {
      case .float: factor(-exponent($0, as: Float.self))
      case .double: factor(-exponent($0, as: Double.self))
      }
    }
    var extent = Extent(eye: scene.camera.center, threads: threads)
    extent.measure(scene.root)
    if let failure = firstFailure(
      in: scene, extent, smallest: precision.smallestNormal,
      commonScale: scale, ownScale: scale)
    {
      return "\(failure.what) for \(precision.rawValue): with that length "
        + "scaled to about 1, \(failure.measure) is below "
        + "\(precision.rawValue)'s normal range"
    }
    return tooFarForItsAxes(
      scene, extent, smallest: precision.smallestNormal
    ).map {
      "\($0.what) for \(precision.rawValue): \($0.measure) is below "
        + "\(precision.rawValue)'s normal range at any scale"
    }
  }

  /// The first ellipsoid whose centre is more than 2⁶¹ (float) or 2⁵⁰⁹
  /// (double) of its shortest semi-axes from the eye: the fast engine's
  /// test in the frame of its axes (`EllipsoidFrame`) squares that ratio,
  /// which no scale changes, and could not hold it (the ellipsoid was left
  /// out of the image without a word). Only scenes whose ellipsoids reach
  /// that far (`Extent.reachInAxes`, never less than the ratio) are
  /// searched.
  static func tooFarForItsAxes(
    _ scene: Scene, _ extent: Extent, smallest: Double
  ) -> Failure? {
    guard 16 * smallest * extent.reachInAxes * extent.reachInAxes > 1
    else { return nil }
    let eye = scene.camera.center
    var found: Failure?
    forEachPrimitive(in: .group(scene.root)) { primitive in
      guard found == nil, case .ellipsoid(let ellipsoid) = primitive else {
        return
      }
      let m = ellipsoid.matrix
      let distance = length(Vector3(m.m03, m.m13, m.m23) - eye)
      let ratio = distance > 0 ? ellipsoid.shortestAxis / distance : 1
      guard ratio * ratio < 16 * smallest else { return }
      found = Failure(
        primitive, beside: "its distance from the eye (\(distance))",
        measure: "its shortest axis over that distance, squared,")
    }
    return found
  }

  /// What no rescaling of `scene` leaves in range when it is computed at
  /// its own lengths, in Double, unscaled, or nil: an object whose squares
  /// at scale 1 fall below Double's normal range (as `problem` judges
  /// them at its own scale: a sphere of radius 1e-200, wherever the eye
  /// is), or whose products with its distance from the eye overflow
  /// (`tooLargeUnscaled`: a sphere 1e200 from the eye; `beyondRange`
  /// true). Every scene `problem` refuses in double fails here too. The
  /// caller words it for the engine that computes so.
  package static func unscaledFailure(_ scene: Scene)
    -> (failure: Failure, beyondRange: Bool)?
  {
    let eye = scene.camera.center
    var extent = Extent(eye: eye)
    extent.measure(scene.root)
    // A second pass only where some product may overflow: a triangle's
    // edge is at most twice its reach, so below 2^509 none does.
    var large: Failure?
    if extent.largest >= 0x1p509 || extent.reachInAxes >= 0x1p510 {
      forEachPrimitive(in: .group(scene.root)) { primitive in
        guard large == nil else { return }
        large = tooLargeUnscaled(primitive, eye: eye)
      }
    }
    let failure =
      large
      ?? firstFailure(
        in: scene, extent, smallest: Double.leastNormalMagnitude,
        commonScale: { _ in 1 }, ownScale: { _ in 1 })
    return failure.map { ($0, large != nil) }
  }

  /// The primitive's failure when what a computation at scale 1
  /// multiplies by its distance from the eye overflows Double: a sphere's
  /// |o − c|² (three squares: its reach below 2^510), an ellipsoid's local eye
  /// M⁻¹·o squared (its reach over its shortest axis below 2^510), a
  /// triangle's s × edge (its reach times its longest edge below 2^1020,
  /// Cramer's rule). A plane's t = (d − n·o)/n·d has no product to
  /// overflow.
  static func tooLargeUnscaled(_ primitive: Primitive, eye: Vector3<Double>)
    -> Failure?
  {
    let reach = primitive.reach(from: eye)
    switch primitive {
    case .sphere(let sphere):
      guard reach >= 0x1p510 else { return nil }
      return Failure(
        primitive, beside: nil,
        measure: "the square of its distance from the eye "
          + "(\(length(sphere.center - eye)))")
    case .plane: return nil
    case .triangle(let triangle):
      let edge = edgeAndReach(triangle, eye: eye).edge
      guard edge * reach >= 0x1p1020 else { return nil }
      return Failure(
        primitive, beside: nil,
        measure: "its distance from the eye (up to \(reach) on an axis) "
          + "times its longest edge (\(edge))")
    case .ellipsoid(let ellipsoid):
      guard reach / ellipsoid.shortestAxis >= 0x1p510 else { return nil }
      return Failure(
        primitive, beside: nil,
        measure: "the square of its reach from the eye (\(reach) on an "
          + "axis) over its shortest axis")
    }
  }

  /// The first primitive, in scene order, that fails both at the scene's
  /// common scale (`commonScale` of its largest length seen from the eye)
  /// and at its own (`ownScale` of its reach): one pass for the common
  /// scale and the smallest measures, which scale as its powers; a
  /// second, to find the object, only when one fails. `measured` is the
  /// scene's `Extent` when the caller has it.
  package static func firstFailure(
    in scene: Scene, _ measured: Extent? = nil, smallest: Double,
    commonScale: (Double) -> Double, ownScale: (Double) -> Double
  ) -> Failure? {
    let eye = scene.camera.center
    let extent =
      measured
      ?? {
        var extent = Extent(eye: eye)
        extent.measure(scene.root)
        return extent
      }()
    let scale = commonScale(extent.largest)
    guard extent.fails(scale: scale, smallest: smallest) else { return nil }
    var found: Failure?
    forEachPrimitive(in: .group(scene.root)) { primitive in
      guard found == nil,
        tooSmall(primitive, eye: eye, scale: scale, smallest: smallest)
          != nil
      else { return }
      found = tooSmall(
        primitive, eye: eye, scale: ownScale(primitive.reach(from: eye)),
        smallest: smallest)
    }
    return found
  }

  /// What leaves the range, for a message: the object, the length seen
  /// from the eye that sets the scale it is traced at (nil for a plane,
  /// whose only length is its distance from the eye), and the measure
  /// whose square falls below the range there.
  package struct Failure {
    package var object: String
    package var beside: String?
    package var measure: String

    package init(_ primitive: Primitive, beside: String?, measure: String) {
      object = primitive.description
      self.beside = beside
      self.measure = measure
    }

    /// "a sphere … is too small beside its distance from the eye (3.0)".
    var what: String {
      "\(object) is "
        + (beside.map { "too small beside \($0)" } ?? "too near the eye")
    }
  }

  /// The primitive's failure when its squares at `scale` fall below
  /// `smallest` (see `problem`); nil when they do not.
  static func tooSmall(
    _ primitive: Primitive, eye: Vector3<Double>, scale: Double,
    smallest: Double
  ) -> Failure? {
    switch primitive {
    case .sphere(let sphere):
      let radius = sphere.radius * scale
      guard radius * radius < smallest else { return nil }
      return Failure(
        primitive,
        beside: "its distance from the eye "
          + "(\(length(sphere.center - eye)))",
        measure: "its radius squared")
    case .plane(let plane):
      // t = k / n·d: k, the distance from the eye, must stay normal.
      let distance = Self.distance(plane, eye: eye)
      guard distance > 0, distance * scale < smallest else { return nil }
      return Failure(
        primitive, beside: nil,
        measure: "its distance from the eye (\(distance))")
    case .triangle(let triangle):
      let (unscaledEdge, unscaledReach) = edgeAndReach(triangle, eye: eye)
      let (edge, reach) = (unscaledEdge * scale, unscaledReach * scale)
      // A degenerate triangle (no edge, or its vertices on a line) is
      // never hit at any scale.
      guard unscaledEdge > 0, edge * edge * Swift.min(reach, 1) < smallest,
        !isLine(triangle, longestEdge: unscaledEdge)
      else {
        return nil
      }
      let (a, b, c) = (triangle.v0, triangle.v1, triangle.v2)
      let farthest = Swift.max(
        length(a - eye), length(b - eye), length(c - eye))
      let longest = Swift.max(length(b - a), length(c - b), length(a - c))
      return Failure(
        primitive, beside: "its distance from the eye (up to \(farthest))",
        measure: "its longest edge (\(longest)) squared")
    case .ellipsoid(let ellipsoid):
      let axis = ellipsoid.shortestAxis
      guard (axis * scale) * (axis * scale) < 4 * smallest else {
        return nil
      }
      let m = ellipsoid.matrix
      let distance = length(Vector3(m.m03, m.m13, m.m23) - eye)
      return Failure(
        primitive,
        beside: ellipsoid.reach(from: eye) > 2 * distance
          ? "its longest axis (up to \(ellipsoid.reach(from: eye)))"
          : "its distance from the eye (\(distance))",
        measure: "its shortest axis squared")
    }
  }

  /// Whether the triangle's vertices are on a line: its edges, brought
  /// near 1 by a power of two (exactly), have no cross product.
  static func isLine(_ triangle: Triangle<Double>, longestEdge: Double)
    -> Bool
  {
    let f = factor(-Int(longestEdge.exponent))
    let (a, b, c) = (triangle.v0 * f, triangle.v1 * f, triangle.v2 * f)
    return (b - a).cross(c - a) == .zero
  }

  /// |v|, without squaring v at its own scale (where the squares of an
  /// offset of 1e-200 would underflow).
  package static func length(_ v: Vector3<Double>) -> Double {
    let largest = v.maxMagnitude
    guard largest > 0, largest.isFinite else { return largest }
    return (v / largest).length * largest
  }
}

extension LengthScale.Primitive: CustomStringConvertible {
  /// The primitive as a message names it, by its own values.
  package var description: String {
    switch self {
    case .sphere(let sphere):
      let c = sphere.center
      return "a sphere of radius \(sphere.radius) (centre \(c.x) \(c.y) "
        + "\(c.z))"
    case .plane(let plane):
      let n = plane.normal
      return "a plane (normal \(n.x) \(n.y) \(n.z), offset "
        + "\(plane.offset))"
    case .triangle(let triangle):
      let (a, b, c) = (triangle.v0, triangle.v1, triangle.v2)
      return "a triangle (vertices \(a.x) \(a.y) \(a.z), \(b.x) \(b.y) "
        + "\(b.z), \(c.x) \(c.y) \(c.z))"
    case .ellipsoid(let ellipsoid):
      return "a transformed sphere whose shortest axis is "
        + "\(ellipsoid.shortestAxis)"
    }
  }
}
