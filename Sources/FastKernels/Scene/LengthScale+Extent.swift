import Geometry
import SceneDescription
import PlatformSupport

/// What the scale of a scene is judged from: its lengths seen from the
/// eye, and the smallest of the measures whose squares must stay normal
/// (see `LengthScale`, `LengthScale.tooSmall`).
extension LengthScale {
  /// The scene's largest length seen from the eye (`Primitive.reach`)
  /// and, per kind, the smallest of the measures `tooSmall` compares at a
  /// scale f: a radius squared (f²), a triangle's longest edge squared
  /// (f²) and that times its reach (f³), an ellipsoid's shortest axis
  /// squared (f²), a plane's distance from the eye (f). Some primitive
  /// fails at f when one of these minima does (and, when a minimum is
  /// itself below the range, perhaps when none does: a second pass, per
  /// primitive, decides).
  package struct Extent {
    let eye: Vector3<Double>
    package var largest: Double
    var radiusSquared = Double.infinity
    var edgeSquared = Double.infinity
    var edgeSquaredReach = Double.infinity
    var axisSquared = Double.infinity
    var planeDistance = Double.infinity
    /// The largest reach of an ellipsoid over its shortest axis: its eye
    /// in its own space is that far from its centre, in radii.
    package var reachInAxes = 0.0

    /// Threads that measure a long list (a mesh's triangles, a group's
    /// entries, the spheres), each a part of it (`addInParts`).
    let threads: Int

    /// Nothing measured yet: the eye's own coordinates are not a length
    /// of the scene (see `LengthScale`).
    package init(eye: Vector3<Double>, threads: Int = 1) {
      self.eye = eye
      self.threads = threads
      largest = 0
    }

    /// What `other` measured, added: the largest of the largest, the
    /// smallest of the minima. Each fold starts from 0 and ∞ and never
    /// takes a NaN in (`max` and `min` keep their first argument then),
    /// so folding in parts and merging gives the sequential fold's values.
    mutating func merge(_ other: Extent) {
      largest = Swift.max(largest, other.largest)
      radiusSquared = Swift.min(radiusSquared, other.radiusSquared)
      edgeSquared = Swift.min(edgeSquared, other.edgeSquared)
      edgeSquaredReach = Swift.min(edgeSquaredReach, other.edgeSquaredReach)
      axisSquared = Swift.min(axisSquared, other.axisSquared)
      planeDistance = Swift.min(planeDistance, other.planeDistance)
      reachInAxes = Swift.max(reachInAxes, other.reachInAxes)
    }

    /// Every primitive of `group`, placed as the render places them: the
    /// spheres straight in it where its list holds them, in parts (not
    /// copied out to be passed, `SceneObject.sphere`: 10⁶ spheres 30 ms
    /// sooner), the rest flattened (`Group.flattened`).
    package mutating func measure(_ group: Group<Double>) {
      var others: [SceneObject<Double>] = []
      group.objects.withUnsafeBufferPointer { buffer in
        guard let children = buffer.baseAddress else { return }
        addInParts(buffer.count) { extent, range in
          for index in range {
            if let sphere = children[index].sphere { extent.add(sphere) }
          }
        }
        for index in buffer.indices where children[index].sphere == nil {
          others.append(children[index])
        }
      }
      add(Group(others).flattened(threads: threads))
    }

    /// Every primitive of `all`.
    mutating func add(_ all: Primitives<Double>) {
      for kind in PrimitiveKind.allCases {
        switch kind {
        case .sphere:
          all.spheres.withUnsafeBufferPointer { spheres in
            addInParts(spheres.count) { extent, range in
              for index in range { extent.add(spheres[index]) }
            }
          }
        case .plane: for plane in all.planes { add(plane) }
        case .triangle: for mesh in all.triangles.parts { add(mesh) }
        case .ellipsoid:
          for ellipsoid in all.transformedSpheres {
            let reach = ellipsoid.reach(from: eye)
            largest = Swift.max(largest, reach)
            let axis = ellipsoid.shortestAxis
            axisSquared = Swift.min(axisSquared, axis * axis)
            reachInAxes = Swift.max(reachInAxes, reach / axis)
          }
        case .shape:
          // Tested in the world's units, at no scale.
          break
        }
      }
    }

    mutating func add(_ plane: Plane<Double>) {
      let distance = LengthScale.distance(plane, eye: eye)
      largest = Swift.max(largest, distance)
      if distance > 0 { planeDistance = Swift.min(planeDistance, distance) }
    }

    mutating func add(_ sphere: Sphere<Double>) {
      largest = Swift.max(largest, sphere.reach(from: eye))
      radiusSquared = Swift.min(radiusSquared, sphere.radius * sphere.radius)
    }

    /// Every triangle of `mesh`, by its vertices alone.
    mutating func add(_ mesh: TriangleMesh<Double>) {
      addInParts(mesh.count) { extent, range in
        for index in range { extent.add(mesh.vertices(at: index)) }
      }
    }

    /// `measure` of the items 0..<`count`: from 2¹⁶ items in parts, one
    /// per thread, each into an extent of its own, merged.
    private mutating func addInParts(
      _ count: Int, _ measure: (inout Extent, Range<Int>) -> Void
    ) {
      let parts = Parallel.parts(
        count, threads: threads, from: 1 << 16, minimum: 1 << 15)
      guard parts > 1 else { return measure(&self, 0..<count) }
      var measured = [Extent](repeating: Extent(eye: eye), count: parts)
      measured.withUnsafeMutableBufferPointer { measured in
        Parallel.inParts(count, parts) { part, range in
          measure(&measured[part], range)
        }
      }
      for extent in measured { merge(extent) }
    }

    mutating func add(_ triangle: Triangle<Double>) {
      add((triangle.v0, triangle.v1, triangle.v2))
    }

    mutating func add(
      _ vertices: (Vector3<Double>, Vector3<Double>, Vector3<Double>)
    ) {
      let (edge, reach) = LengthScale.edgeAndReach(vertices, eye: eye)
      largest = Swift.max(largest, reach)
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

  /// A plane's distance from the eye, |d − n·eye|, compensated and
  /// rounded once (`CameraRelative.plane`): uncompensated, n·eye rounds by
  /// half its ulp, which can be 2⁵³ times the distance (a plane 10²⁶⁸ from
  /// an eye 10³⁰⁰ from the origin along a tilted normal).
  static func distance(_ plane: Plane<Double>, eye: Vector3<Double>)
    -> Double
  {
    let distance: Double = CameraRelative.plane(
      normal: plane.normal, offset: plane.offset, eye: eye)
    return distance.magnitude
  }

  /// A triangle's longest edge and the farthest of its vertices from the
  /// eye, in max-norm.
  package static func edgeAndReach(
    _ triangle: Triangle<Double>, eye: Vector3<Double>
  ) -> (edge: Double, reach: Double)
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
}
