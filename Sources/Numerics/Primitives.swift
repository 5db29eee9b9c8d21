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
      switch object {
      case .sphere: true
      case .plane, .triangle, .mesh, .shape: false
      case .group(let group): group.objects.contains(where: holdsSphere)
      case .transform(let inner): holdsSphere(inner.object)
      }
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
      switch object {
      case .sphere: counts.spheres += 1
      case .plane: counts.planes += 1
      case .triangle, .mesh, .shape: break
      case .group(let group): for child in group.objects { count(child) }
      case .transform(let inner): count(inner.object)
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
    func collect(
      _ object: SceneObject<Scalar>,
      _ transform: (Matrix4<Scalar>, Matrix4<Scalar>)?
    ) {
      switch object {
      case .sphere(let sphere):
        guard let (matrix, inverse) = transform else {
          result.spheres.append(sphere)
          return
        }
        if let scale = matrix.similarityScale {
          result.spheres.append(
            Sphere(
              center: matrix.transformPoint(sphere.center),
              radius: sphere.radius * scale,
              materialIndex: sphere.materialIndex))
        } else {
          result.transformedSpheres.append(
            TransformedSphere(sphere: sphere, matrix: matrix, inverse: inverse))
        }
      case .plane(let plane):
        guard let (matrix, _) = transform else {
          result.planes.append(plane)
          return
        }
        let normal = matrix.transformNormal(plane.normal)
        let point = matrix.transformPoint(plane.normal * plane.offset)
        result.planes.append(
          Plane(
            normal: normal, offset: normal.dot(point),
            materialIndex: plane.materialIndex))
      case .triangle(let triangle):
        guard let (matrix, _) = transform else {
          result.triangles.append(triangle)
          return
        }
        result.triangles.append(triangle.moved(by: matrix))
      case .mesh(let mesh):
        // Untransformed, the mesh's own storage, shared.
        result.triangles.append(
          transform.map { mesh.moved(by: $0.0) } ?? mesh)
      case .group(let group):
        for child in group.objects { collect(child, transform) }
      case .transform(let inner):
        let combined =
          transform.map { ($0.0 * inner.matrix, inner.inverse * $0.1) }
          ?? (inner.matrix, inner.inverse)
        collect(inner.object, combined)
      case .shape(let shape):
        guard let (matrix, inverse) = transform else {
          result.shapes.append(PlacedShape(shape.object))
          return
        }
        // Only a Double scene is read: the generic matrix is Double's.
        result.shapes.append(
          PlacedShape(
            shape.object,
            placement: (Matrix4<Double>(matrix), Matrix4<Double>(inverse))))
      }
    }
    objects.withUnsafeBufferPointer { buffer in
      guard let objects = buffer.baseAddress else { return }
      for index in buffer.indices {
        // Most of a large scene: spheres straight in the root group.
        if let sphere = objects[index].sphere {
          result.spheres.append(sphere)
        } else {
          collect(objects[index], nil)
        }
      }
    }
  }
}

extension Triangle {
  /// The triangle placed by `matrix`: its vertices moved, its vertex
  /// normals by the inverse transpose.
  func moved(by matrix: Matrix4<Scalar>) -> Triangle {
    var moved = self
    moved.v0 = matrix.transformPoint(v0)
    moved.v1 = matrix.transformPoint(v1)
    moved.v2 = matrix.transformPoint(v2)
    if let normals = vertexNormals {
      // Not normalised one by one: the hit's interpolation then gives
      // the transform of the object's interpolated normal.
      // A scale far from 1 (`UniformScale 1e20`) would take the
      // cofactors, its square, out of range: they are taken of the
      // matrix rescaled by a power of two, the same directions.
      let normalMatrix = matrix.withLinearPartNearOne()
      moved.vertexNormals = Triangle.VertexNormals(
        normalMatrix.cofactorNormal(normals.n0),
        normalMatrix.cofactorNormal(normals.n1),
        normalMatrix.cofactorNormal(normals.n2))
    }
    return moved
  }
}

extension Matrix4 {
  /// s when the linear part is s times a rotation (LᵀL = s²·I to within
  /// 16 ε relative) and the matrix is affine: a sphere then stays a sphere
  /// of radius r·s, and is best kept as one.
  @usableFromInline
  package var similarityScale: Scalar? {
    guard isAffine else { return nil }
    let columns = [
      Vector3(m00, m10, m20), Vector3(m01, m11, m21), Vector3(m02, m12, m22),
    ]
    let squared = columns[0].lengthSquared
    guard squared > 0, squared.isFinite else { return nil }
    let tolerance = 16 * Scalar.ulpOfOne * squared
    for i in 0..<3 {
      for j in 0..<3 {
        let product = columns[i].dot(columns[j])
        let expected: Scalar = i == j ? squared : 0
        if (product - expected).magnitude > tolerance { return nil }
      }
    }
    return squared.squareRoot()
  }
}

extension TriangleMesh {
  /// The mesh placed by `matrix`, as `Triangle.moved(by:)` places each of
  /// its triangles: every vertex moved, every normal by the cofactors of
  /// the matrix rescaled near 1. Each shared value is moved once, by the
  /// same operations, so each triangle is the one `moved` gives.
  func moved(by matrix: Matrix4<Scalar>) -> TriangleMesh {
    var moved = self
    moved.storage = StorageTag()
    moved.vertices = vertices.map { matrix.transformPoint($0) }
    if normalsFollowVertices || !normalIndices.isEmpty {
      let normalMatrix = matrix.withLinearPartNearOne()
      moved.normals = normals.map { normalMatrix.cofactorNormal($0) }
    }
    return moved
  }

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
