/// The limits of rescaling: what no power of two can bring into the
/// render precision's range (see `LengthScale`).
extension LengthScale {
  /// Why `scene` cannot be drawn right in `precision`, or nil: an object
  /// so small beside its own distance from the eye that the squares and
  /// products of its test fall below the precision's normal range at any
  /// scale, where they keep few digits or none. A sphere whose radius
  /// squared does (a radius of 1e-25 three units from the eye in Float:
  /// (L/r)² = 10⁵⁰); a triangle whose longest edge squared, times its reach
  /// from the eye where that is below 1, does (its edge functions and their
  /// sum weighted by depth, `TriangleIntersection`); an ellipsoid whose
  /// shortest axis squared does (its local ray's direction, M⁻¹·d, would
  /// overflow); a plane whose distance from the eye does (t = k / n·d).
  /// Objects that fail only at the scene's common scale are traced at
  /// their own (`layers`); these fail at their own too, and the command
  /// line refuses the scene rather than draw them wrong.
  public static func problem(_ scene: Scene, precision: Precision)
    -> String?
  {
    // One pass for the scale and the smallest measures, which scale as
    // its powers; a second, to find the object, only when one fails.
    let eye = scene.camera.center
    var extent = Extent(eye: eye)
    extent.measure(.group(scene.root))
    func exponent(_ largest: Double) -> Int {
      switch precision {
      case .float: Self.exponent(largest, as: Float.self)
      case .double: Self.exponent(largest, as: Double.self)
      }
    }
    let scale = factor(-exponent(extent.largest))
    let smallest = precision.smallestNormal
    guard extent.fails(scale: scale, smallest: smallest) else { return nil }
    var found: String?
    forEachPrimitive(in: .group(scene.root)) { primitive in
      guard found == nil,
        tooSmall(primitive, eye: eye, scale: scale, smallest: smallest)
          != nil
      else { return }
      let own = Swift.max(eye.maxMagnitude, primitive.largestLength)
      guard
        let what = tooSmall(
          primitive, eye: eye, scale: factor(-exponent(own)),
          smallest: smallest)
      else { return }
      found =
        "\(what) is too small beside its coordinates and the eye's (up to "
        + "\(own)) for \(precision.rawValue): its squares leave the range "
        + "at any scale"
        + (precision == .float ? "; use --precision double" : "")
    }
    return found
  }

  /// The scene's largest length and, per kind, the smallest of the
  /// measures `tooSmall` compares at a scale f: a radius squared (f²), a
  /// triangle's longest edge squared (f²) and that times its reach (f³),
  /// an ellipsoid's shortest axis squared (f²), a plane's distance from
  /// the eye (f). Some primitive fails at f exactly when one of these
  /// minima does.
  struct Extent {
    let eye: Vector3<Double>
    var largest: Double
    var radiusSquared = Double.infinity
    var edgeSquared = Double.infinity
    var edgeSquaredReach = Double.infinity
    var axisSquared = Double.infinity
    var planeDistance = Double.infinity

    init(eye: Vector3<Double>) {
      self.eye = eye
      largest = eye.maxMagnitude
    }

    mutating func measure(_ object: SceneObject<Double>) {
      switch object {
      case .sphere(let sphere): add(sphere)
      case .plane(let plane): add(plane)
      case .triangle(let triangle): add(triangle)
      case .mesh(let mesh): add(mesh)
      case .group(let group):
        for child in group.objects { measure(child) }
      case .transform: add(Group([object]).flattened())
      case .shape: break
      }
    }

    /// Every primitive of `all`.
    mutating func add(_ all: Primitives<Double>) {
      for sphere in all.spheres { add(sphere) }
      for plane in all.planes { add(plane) }
      for mesh in all.triangles.parts { add(mesh) }
      for ellipsoid in all.transformedSpheres {
        largest = Swift.max(largest, ellipsoid.largestLength)
        let axis = ellipsoid.shortestAxis
        axisSquared = Swift.min(axisSquared, axis * axis)
      }
    }

    mutating func add(_ plane: Plane<Double>) {
      largest = Swift.max(largest, plane.offset.magnitude)
      let distance = LengthScale.distance(plane, eye: eye)
      if distance > 0 { planeDistance = Swift.min(planeDistance, distance) }
    }

    mutating func add(_ sphere: Sphere<Double>) {
      largest = Swift.max(largest, sphere.largestLength)
      radiusSquared = Swift.min(radiusSquared, sphere.radius * sphere.radius)
    }

    /// Every triangle of `mesh`, by its vertices alone.
    mutating func add(_ mesh: TriangleMesh<Double>) {
      for index in mesh.indices { add(mesh.vertices(at: index)) }
    }

    mutating func add(_ triangle: Triangle<Double>) {
      add((triangle.v0, triangle.v1, triangle.v2))
    }

    mutating func add(
      _ vertices: (Vector3<Double>, Vector3<Double>, Vector3<Double>)
    ) {
      // As `Triangle.largestLength`, in the same order.
      largest = Swift.max(
        largest,
        Swift.max(
          vertices.0.maxMagnitude, vertices.1.maxMagnitude,
          vertices.2.maxMagnitude))
      let (edge, reach) = LengthScale.edgeAndReach(vertices, eye: eye)
      guard edge > 0 else { return }
      edgeSquared = Swift.min(edgeSquared, edge * edge)
      edgeSquaredReach = Swift.min(edgeSquaredReach, edge * edge * reach)
    }

    /// Whether some primitive fails at scale `f` (see `tooSmall`).
    func fails(scale f: Double, smallest: Double) -> Bool {
      radiusSquared * f * f < smallest || edgeSquared * f * f < smallest
        || edgeSquaredReach * f * f * f < smallest
        || axisSquared * f * f < 4 * smallest
        || planeDistance * f < smallest
    }
  }

  /// A plane's distance from the eye, |d − n·eye| (nearly: in Double,
  /// uncompensated, which is enough to judge its range).
  static func distance(_ plane: Plane<Double>, eye: Vector3<Double>)
    -> Double
  {
    (plane.offset - plane.normal.dot(eye)).magnitude
  }

  /// A triangle's longest edge and the farthest of its vertices from the
  /// eye, in max-norm.
  static func edgeAndReach(_ triangle: Triangle<Double>, eye: Vector3<Double>)
    -> (edge: Double, reach: Double)
  {
    edgeAndReach((triangle.v0, triangle.v1, triangle.v2), eye: eye)
  }

  /// `edgeAndReach` of the triangle with vertices `vertices`.
  static func edgeAndReach(
    _ vertices: (Vector3<Double>, Vector3<Double>, Vector3<Double>),
    eye: Vector3<Double>
  ) -> (edge: Double, reach: Double) {
    let (a, b, c) = vertices
    return (
      Swift.max(
        (b - a).maxMagnitude, (c - b).maxMagnitude, (a - c).maxMagnitude),
      Swift.max(
        (a - eye).maxMagnitude, (b - eye).maxMagnitude,
        (c - eye).maxMagnitude)
    )
  }

  /// The primitive, described, when its squares at `scale` fall below
  /// `smallest` (see `problem`); nil when they do not.
  static func tooSmall(
    _ primitive: Primitive, eye: Vector3<Double>, scale: Double,
    smallest: Double
  ) -> String? {
    switch primitive {
    case .sphere(let sphere):
      let radius = sphere.radius * scale
      guard radius * radius < smallest else { return nil }
      let c = sphere.center
      return "a sphere of radius \(sphere.radius) (centre \(c.x) \(c.y) "
        + "\(c.z))"
    case .plane(let plane):
      // t = k / n·d: k, the distance from the eye, must stay normal.
      let distance = Self.distance(plane, eye: eye)
      guard distance > 0, distance * scale < smallest else { return nil }
      let n = plane.normal
      return "a plane (normal \(n.x) \(n.y) \(n.z), offset "
        + "\(plane.offset))"
    case .triangle(let triangle):
      let (a, b, c) = (triangle.v0, triangle.v1, triangle.v2)
      let (unscaledEdge, unscaledReach) = edgeAndReach(triangle, eye: eye)
      let (edge, reach) = (unscaledEdge * scale, unscaledReach * scale)
      // A degenerate triangle (no edge) is never hit at any scale.
      guard unscaledEdge > 0, edge * edge * Swift.min(reach, 1) < smallest
      else {
        return nil
      }
      return "a triangle (vertices \(a.x) \(a.y) \(a.z), \(b.x) \(b.y) "
        + "\(b.z), \(c.x) \(c.y) \(c.z))"
    case .ellipsoid(let ellipsoid):
      let axis = ellipsoid.shortestAxis
      guard (axis * scale) * (axis * scale) < 4 * smallest else {
        return nil
      }
      return "a transformed sphere whose shortest axis is \(axis)"
    }
  }

}
