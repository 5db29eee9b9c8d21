import Geometry
import SceneDescription
import PlatformSupport

/// A sphere under a transform that is not a similarity: an ellipsoid,
/// intersected in the sphere's own space.
@usableFromInline
package struct TransformedSphere<Scalar: RayScalar>: Hashable, Sendable {
  @usableFromInline
  package var sphere: Sphere<Scalar>
  @usableFromInline
  package var matrix: Matrix4<Scalar>
  @usableFromInline
  package var inverse: Matrix4<Scalar>
}

/// Every primitive of a scene graph with its transforms applied: in world
/// space where that is exact enough (triangles, planes, spheres under
/// similarities), as transformed spheres otherwise.
@usableFromInline
package struct Primitives<Scalar: RayScalar>: Sendable {
  @usableFromInline
  package var spheres: [Sphere<Scalar>] = []
  @usableFromInline
  package var planes: [Plane<Scalar>] = []
  /// Loose triangles and meshes in file order.
  @usableFromInline
  package var triangles = TriangleList<Scalar>()
  @usableFromInline
  package var transformedSpheres: [TransformedSphere<Scalar>] = []
  /// Shapes of other kinds (`SceneObject.shape`), placed by their
  /// transforms, in Double and in the world's units whatever the render.
  @usableFromInline
  package var shapes: [PlacedShape] = []
}

/// The kinds of primitive a flattened scene holds (`Primitives`), in the
/// order each walk over it takes them: the fast engine's one list of
/// kinds. Every walk over a flattened scene (placing, scaling, moving to
/// the eye, measuring, layering, compiling) switches over it kind by kind,
/// so that the compiler names each walk a new kind must join.
package enum PrimitiveKind: CaseIterable, Sendable {
  case sphere
  case plane
  /// Loose triangles and meshes.
  case triangle
  /// A sphere under a transform that is not a similarity.
  case ellipsoid
  /// A shape of one's own.
  case shape
}

/// A shape of one's own (`SceneObject.shape`) where the scene's transforms
/// put it: the fast engine hits it through its `Hittable` conformance, the
/// ray taken into the shape's space (`CompiledScene.testShapes`).
@usableFromInline
package struct PlacedShape: Sendable {
  @usableFromInline
  package var shape: any Hittable
  /// M, which places the shape's points P at M·P, and M⁻¹; nil when no
  /// transform places it.
  @usableFromInline
  package var placement: (matrix: Matrix4<Double>, inverse: Matrix4<Double>)?

  @usableFromInline
  package init(
    _ shape: any Hittable,
    placement: (matrix: Matrix4<Double>, inverse: Matrix4<Double>)? = nil
  ) {
    self.shape = shape
    self.placement = placement
  }
}

extension Group {
  /// The primitives as one group in the world, kind by kind: spheres,
  /// planes, triangles, then each ellipsoid as a transform of its sphere.
  @usableFromInline
  package init(_ all: Primitives<Scalar>) {
    var objects: [SceneObject] = all.spheres.map { .sphere($0) }
    objects += all.planes.map { .plane($0) }
    // Each run of loose triangles as a mesh of them: hit as the triangles
    // one by one (`TriangleMesh`).
    objects += all.triangles.parts.map { .mesh($0) }
    objects += all.transformedSpheres.map {
      .transform(
        Transform(
          matrix: $0.matrix, inverse: $0.inverse, object: .sphere($0.sphere)))
    }
    objects += all.shapes.map { placed in
      guard let (matrix, inverse) = placed.placement else {
        return .shape(Shape(placed.shape))
      }
      return .transform(
        Transform(
          matrix: Matrix4(matrix), inverse: Matrix4(inverse),
          object: .shape(Shape(placed.shape))))
    }
    self.init(objects)
  }
}

extension Group {
  /// Every primitive, nested groups and transforms flattened, in file order
  /// within each kind. A large group's own spheres are read by up to
  /// `threads` threads (`directSpheres`), with the same result.
  @usableFromInline
  package func flattened(threads: Int = 1) -> Primitives<Scalar> {
    var result = Primitives<Scalar>()
    let parts = Parallel.parts(
      objects.count, threads: threads, from: 1 << 16, minimum: 1 << 15)
    if parts > 1, let direct = directSpheres(parts: parts) {
      // The other entries hold no sphere: in order after the spheres, each
      // kind keeps its order.
      result.spheres = direct.spheres
      for index in direct.others {
        Group([objects[index]]).collect(into: &result)
      }
      return result
    }
    collect(into: &result)
    return result
  }

  /// The spheres straight in this group, in order, read in `parts` parts
  /// on as many threads, and the positions of its other entries; nil when
  /// one of those holds a sphere (in a group, under a transform), whose
  /// place among the spheres only the walk in order keeps.
  private func directSpheres(parts: Int)
    -> (spheres: [Sphere<Scalar>], others: [Int])?
  {
    func holdsSphere(_ object: SceneObject<Scalar>) -> Bool {
      var holds = false
      object.forEachPlaced(under: nil) { leaf, _ in
        if leaf.sphere != nil { holds = true }
      }
      return holds
    }
    return objects.withUnsafeBufferPointer { buffer in
      guard let objects = buffer.baseAddress else { return nil }
      var found = [(spheres: Int, others: [Int], holdsNone: Bool)](
        repeating: (0, [], true), count: parts)
      found.withUnsafeMutableBufferPointer { found in
        Parallel.inParts(buffer.count, parts) { part, range in
          var mine = (spheres: 0, others: [Int](), holdsNone: true)
          for index in range {
            if objects[index].sphere != nil {
              mine.spheres += 1
            } else {
              mine.others.append(index)
              if holdsSphere(objects[index]) { mine.holdsNone = false }
            }
          }
          found[part] = mine
        }
      }
      guard found.allSatisfy(\.holdsNone) else { return nil }
      let total = found.reduce(0) { $0 + $1.spheres }
      let spheres = [Sphere<Scalar>](unsafeUninitializedCapacity: total) {
        spheres, count in
        Memory.adviseHugePages(UnsafeMutableRawBufferPointer(spheres))
        Parallel.inParts(buffer.count, parts) { part, range in
          var next = found[..<part].reduce(0) { $0 + $1.spheres }
          for index in range {
            if let sphere = objects[index].sphere {
              (spheres.baseAddress! + next).initialize(to: sphere)
              next += 1
            }
          }
        }
        count = total
      }
      return (spheres, found.flatMap(\.others))
    }
  }

  /// Appends every primitive of this group, in order within each kind.
  private func collect(into result: inout Primitives<Scalar>) {
    // Counted first so that each array is allocated once: growing the
    // array of 10⁶ spheres by doubling copied it over and over, and made
    // this a tenth of compiling the scene. A transformed sphere is counted
    // as a sphere, which it mostly stays. Triangles need no count: a
    // mesh joins the list whole (`TriangleList`).
    var counts = (spheres: 0, planes: 0)
    func count(_ object: SceneObject<Scalar>) {
      object.forEachPlaced(under: nil) { leaf, _ in
        if leaf.sphere != nil {
          counts.spheres += 1
        } else if case .plane = leaf {
          counts.planes += 1
        }
      }
    }
    // Each object looked at where the list holds it: a `for object in
    // objects` copied every entry out and destroyed it again (the enum's
    // outlined copy, a call per entry), 35–40 ms of compiling 10⁶ spheres.
    // (Handed to a closure, each was copied again.)
    objects.withUnsafeBufferPointer { buffer in
      guard let objects = buffer.baseAddress else { return }
      for index in buffer.indices {
        if objects[index].sphere != nil {
          counts.spheres += 1
        } else {
          count(objects[index])
        }
      }
    }
    result.spheres.reserveCapacityOnHugePages(counts.spheres)
    result.planes.reserveCapacity(counts.planes)
    objects.withUnsafeBufferPointer { buffer in
      guard let objects = buffer.baseAddress else { return }
      for index in buffer.indices {
        // Most of a large scene: spheres straight in the root group.
        if let sphere = objects[index].sphere {
          result.spheres.append(sphere)
        } else {
          objects[index].forEachPlaced(under: nil) { leaf, placement in
            result.add(leaf, placedBy: placement)
          }
        }
      }
    }
  }
}

extension Primitives {
  /// Adds one object of the scene where `placement` puts it
  /// (`Group.forEachPlaced`): in the world where it stays the same kind
  /// of object there (`Sphere.placed`, `Plane.placed`, `Triangle.moved`,
  /// `TriangleMesh.moved`), a sphere stretched into an ellipsoid as a
  /// transformed sphere, a shape of one's own with its placement. The one
  /// place the fast engine looks at a scene object's kind.
  mutating func add(
    _ object: SceneObject<Scalar>, placedBy placement: Placement<Scalar>?
  ) {
    switch object {
    case .sphere(let sphere):
      guard let (matrix, inverse) = placement else {
        spheres.append(sphere)
        return
      }
      if let placed = sphere.placed(by: matrix) {
        spheres.append(placed)
      } else {
        transformedSpheres.append(
          TransformedSphere(sphere: sphere, matrix: matrix, inverse: inverse))
      }
    case .plane(let plane):
      planes.append(placement.map { plane.placed(by: $0.matrix) } ?? plane)
    case .triangle(let triangle):
      triangles.append(
        placement.map { triangle.moved(by: $0.matrix) } ?? triangle)
    case .mesh(let mesh):
      // Unplaced, the mesh's own storage, shared.
      triangles.append(placement.map { mesh.moved(by: $0.matrix) } ?? mesh)
    case .shape(let shape):
      // Only a Double scene is read: the generic matrix is Double's.
      shapes.append(
        PlacedShape(
          shape.object,
          placement: placement.map {
            (Matrix4<Double>($0.matrix), Matrix4<Double>($0.inverse))
          }))
    case .group, .transform:
      preconditionFailure("Group.forEachPlaced yields neither")
    }
  }
}

extension TriangleMesh {
  /// Every vertex times `factor`, as `Triangle.scaled(by:)`.
  func scaled(by factor: Scalar) -> TriangleMesh {
    var scaled = self
    scaled.storage = StorageTag()
    scaled.vertices = vertices.map { $0 * factor }
    return scaled
  }
}


extension SceneObject {
  /// The sphere this entry is, if it is one. Asked of an entry where its
  /// list holds it (`Group.flattened`), it does not copy the entry out and
  /// destroy it again as `if case .sphere` did.
  var sphere: Sphere<Scalar>? {
    if case .sphere(let sphere) = self { return sphere }
    return nil
  }
}
