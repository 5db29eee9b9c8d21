/// An object placed by an affine matrix (the course's `Transform`): the
/// object's points P appear at M·P.
///
/// The course takes the ray into the object's space by M⁻¹ (direction not
/// renormalised, so t means the same point in both spaces) and brings the
/// normal back by the inverse transpose. Here the object is placed in the
/// world instead wherever it stays the same kind of object there, which
/// rounds less: triangles by their moved vertices, planes by their moved
/// normal and point, spheres under similarities by their moved centre and
/// scaled radius. Only a sphere stretched into an ellipsoid stays a
/// transformed sphere (`TransformedSphere`), hit in the frame of its axes
/// by the stable method, in its own space by the naive one. The fast
/// engine places objects the same way, once per render
/// (`Group.flattened`).
public struct Transform<Scalar: RayScalar>: Hashable, Sendable {
  public var matrix: Matrix4<Scalar>
  public var inverse: Matrix4<Scalar>
  public var object: SceneObject<Scalar>

  /// Nil when the matrix has no inverse (a scale of zero, say).
  public init?(matrix: Matrix4<Scalar>, object: SceneObject<Scalar>) {
    guard let inverse = matrix.inverse() else { return nil }
    self.init(matrix: matrix, inverse: inverse, object: object)
  }

  /// A transform whose inverse is known (a product of inverses, say).
  init(
    matrix: Matrix4<Scalar>, inverse: Matrix4<Scalar>,
    object: SceneObject<Scalar>
  ) {
    self.matrix = matrix
    self.inverse = inverse
    self.object = object
  }
}

extension Transform: Intersectable {
  /// The nearest hit of the placed object. Placing it costs a pass over
  /// the object for every ray: the course engine's price for testing the
  /// scene as the file describes it.
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    Group([.transform(self)]).flattened().intersect(
      ray, after: tMin, before: tMax, method: method)
  }
}

/// A sphere under a transform that is not a similarity: an ellipsoid,
/// intersected in the sphere's own space.
public struct TransformedSphere<Scalar: RayScalar>: Hashable, Sendable {
  public var sphere: Sphere<Scalar>
  public var matrix: Matrix4<Scalar>
  public var inverse: Matrix4<Scalar>
}

extension TransformedSphere: Intersectable {
  /// The stable method: the ellipsoid in the frame of its axes as seen
  /// from the ray's origin (`EllipsoidFrame`, its constants in
  /// DoubleDouble from the Double matrix), tMin ≥ 0: the fast engine's
  /// numbers in Double (in Float it keeps the object-space test for mild
  /// ellipsoids, `StableEllipsoid`). The naive method, the course's way:
  /// the ray taken into the sphere's space by M⁻¹, the sphere's normal
  /// brought back by the inverse transpose.
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    if method == .stable {
      let placed = TransformedSphere<Double>(
        sphere: Sphere(
          center: Vector3(sphere.center), radius: Double(sphere.radius),
          materialIndex: sphere.materialIndex),
        matrix: Matrix4(matrix), inverse: Matrix4(inverse))
      let frame = EllipsoidFrame<Scalar>(placed, eye: Vector3(ray.origin))
      guard
        let t = frame.root(
          direction: ray.direction, after: tMin, before: tMax)
      else { return nil }
      return Hit(
        t: t, normal: frame.normal(direction: ray.direction, t: t),
        materialIndex: sphere.materialIndex)
    }
    let local = Ray(
      origin: inverse.transformPoint(ray.origin),
      direction: inverse.transformDirection(ray.direction))
    guard
      var hit = sphere.intersect(
        local, after: tMin, before: tMax, method: method)
    else { return nil }
    hit.normal = matrix.transformNormal(hit.normal)
    return hit
  }
}

/// Every primitive of a scene graph with its transforms applied: in world
/// space where that is exact enough (triangles, planes, spheres under
/// similarities), as transformed spheres otherwise.
public struct Primitives<Scalar: RayScalar>: Sendable {
  public var spheres: [Sphere<Scalar>] = []
  public var planes: [Plane<Scalar>] = []
  /// Loose triangles and meshes in file order.
  public var triangles = TriangleList<Scalar>()
  public var transformedSpheres: [TransformedSphere<Scalar>] = []
  /// Shapes of other kinds (`SceneObject.shape`), placed by their
  /// transforms, in Double and in the world's units whatever the render.
  public var shapes: [any Hittable] = []
}

extension Group {
  /// The same group with every transform's object placed in the world, once
  /// (see `Transform`): each transform becomes a group of its spheres,
  /// planes and triangles in world space, then its ellipsoids, each a
  /// transform of one sphere. It is hit exactly as the group is.
  public func placed() -> Group {
    Group(objects.map { $0.placed() })
  }
}

extension SceneObject {
  /// The object with its transforms applied (see `Group.placed`).
  public func placed() -> SceneObject {
    switch self {
    case .sphere, .plane, .triangle, .mesh:
      return self
    case .group(let group):
      return .group(group.placed())
    case .transform:
      return .group(Group(Group([self]).flattened()))
    case .shape:
      return self
    }
  }
}

extension Group {
  /// The primitives as one group in the world, kind by kind: spheres,
  /// planes, triangles, then each ellipsoid as a transform of its sphere.
  public init(_ all: Primitives<Scalar>) {
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
    objects += all.shapes.map { .shape(Shape($0)) }
    self.init(objects)
  }
}

extension Primitives: Intersectable {
  /// The nearest hit, kind by kind as the fast engine tests them: spheres,
  /// planes, triangles, then ellipsoids, each in order.
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    var nearest: Hit<Scalar>?
    func test(_ object: some Intersectable<Scalar>) {
      if let hit = object.intersect(
        ray, after: tMin, before: nearest?.t ?? tMax, method: method)
      {
        nearest = hit
      }
    }
    spheres.forEach(test)
    planes.forEach(test)
    triangles.forEach(test)
    transformedSpheres.forEach(test)
    shapes.forEach { test(SceneObject<Scalar>.shape(Shape($0))) }
    return nearest
  }
}

extension Group {
  /// Every primitive, nested groups and transforms flattened, in file order
  /// within each kind.
  public func flattened() -> Primitives<Scalar> {
    var result = Primitives<Scalar>()
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
    for object in objects {
      if case .sphere = object {
        counts.spheres += 1
      } else {
        count(object)
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
          result.shapes.append(shape.object)
          return
        }
        // Only a Double scene is read: the generic matrix is Double's.
        result.shapes.append(
          PlacedShape(
            shape.object, matrix: Matrix4<Double>(matrix),
            inverse: Matrix4<Double>(inverse)))
      }
    }
    for object in objects {
      // Most of a large scene: spheres straight in the root group.
      if case .sphere(let sphere) = object {
        result.spheres.append(sphere)
      } else {
        collect(object, nil)
      }
    }
    return result
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
  public var similarityScale: Scalar? {
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
