/// A list of objects, nested groups included, hit as one.
public struct Group<Scalar: RayScalar>: Hashable, Sendable {
  public var objects: [SceneObject<Scalar>]

  public init(_ objects: [SceneObject<Scalar>] = []) {
    self.objects = objects
  }

  /// Every sphere and plane, nested groups flattened, in file order.
  public func primitives() -> (
    spheres: [Sphere<Scalar>], planes: [Plane<Scalar>]
  ) {
    let all = flattened()
    return (all.spheres, all.planes)
  }
}

/// One entry of a group. An enum rather than `any Intersectable`, so that
/// even the model's own traversal dispatches statically.
///
/// Spheres and planes are stored inline: boxing each one cost a heap
/// allocation per object, a fifth of the parse of a million spheres.
/// Triangles are boxed so that they do not make every entry three times
/// bigger, and a mesh file's triangles are one entry, their array
/// (`TriangleMesh`); a transform must be boxed, since it holds an object.
public enum SceneObject<Scalar: RayScalar>: Hashable, Sendable {
  case sphere(Sphere<Scalar>)
  case plane(Plane<Scalar>)
  indirect case triangle(Triangle<Scalar>)
  case mesh(TriangleMesh<Scalar>)
  case group(Group<Scalar>)
  indirect case transform(Transform<Scalar>)
  /// A shape of a kind the scene's readers and the fast engine do not
  /// specialise, hit through its `Hittable` conformance in Double.
  case shape(Shape)
}

extension SceneObject: Intersectable {
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    switch self {
    case .sphere(let sphere):
      sphere.intersect(ray, after: tMin, before: tMax, method: method)
    case .plane(let plane):
      plane.intersect(ray, after: tMin, before: tMax, method: method)
    case .triangle(let triangle):
      triangle.intersect(ray, after: tMin, before: tMax, method: method)
    case .mesh(let mesh):
      mesh.intersect(ray, after: tMin, before: tMax, method: method)
    case .group(let group):
      group.intersect(ray, after: tMin, before: tMax, method: method)
    case .transform(let transform):
      transform.intersect(ray, after: tMin, before: tMax, method: method)
    case .shape(let shape):
      shape.object.intersect(
        Ray(origin: Vector3(ray.origin), direction: Vector3(ray.direction)),
        after: Double(tMin), before: Double(tMax)
      ).map {
        Hit(
          t: Scalar($0.t), normal: Vector3($0.normal),
          materialIndex: $0.materialIndex,
          textureCoordinate: $0.textureCoordinate.map(TextureCoordinate.init))
      }
    }
  }
}

extension Group: Intersectable {
  /// The nearest hit among the objects (`nearestHit`).
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    objects.nearestHit(ray, after: tMin, before: tMax, method: method)
  }

  public func occludes(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Bool {
    objects.contains { $0.occludes(ray, after: tMin, before: tMax) }
  }
}

extension Sequence where Element: Intersectable {
  /// The nearest hit among the elements, tested in order; each later one
  /// only has to beat the nearest so far (strictly: a tie goes to the
  /// earlier one). A group's objects and a mesh's triangles are searched
  /// this way.
  func nearestHit(
    _ ray: Ray<Element.Scalar>, after tMin: Element.Scalar,
    before tMax: Element.Scalar, method: IntersectionMethod
  ) -> Hit<Element.Scalar>? {
    var nearest: Hit<Element.Scalar>?
    for object in self {
      if let hit = object.intersect(
        ray, after: tMin, before: nearest?.t ?? tMax, method: method)
      {
        nearest = hit
      }
    }
    return nearest
  }
}
