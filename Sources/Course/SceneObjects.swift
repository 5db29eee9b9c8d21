import Geometry
import SceneDescription

/// The course's objects for a scene as the readers give it: the one place
/// that names each kind of object for the course engine.
struct SceneObjects {
  /// Each mesh made once per reading of its file and material, however
  /// often the scene names it (a mesh under many transforms).
  private var meshes: [MeshKey: TriangleMesh] = [:]

  private struct MeshKey: Hashable {
    var storage: ObjectIdentifier
    var material: Int
  }

  /// The scene's root group as the course's objects.
  static func group(_ group: SceneDescription.Group<Double>) -> Group {
    var objects = SceneObjects()
    return objects.group(group)
  }

  /// One object of the scene as the course's.
  static func object(_ object: SceneObject<Double>) -> (any Hittable)? {
    var objects = SceneObjects()
    return objects.object(object)
  }

  /// A group as the course's `Group`; one of many objects holds them in a
  /// `BoxedGroup`, which finds the same hits without asking each.
  mutating func group(_ group: SceneDescription.Group<Double>) -> Group {
    let objects = group.objects.compactMap { object($0) }
    return objects.count > BoxedGroup.threshold
      ? Group([BoxedGroup(objects)]) : Group(objects)
  }

  /// One object of the scene as the course's; nil for a transform with no
  /// inverse, which nothing can hit.
  mutating func object(_ object: SceneObject<Double>) -> (any Hittable)? {
    switch object {
    case .sphere(let sphere):
      return Sphere(
        center: sphere.center, radius: sphere.radius,
        materialIndex: sphere.materialIndex)
    case .plane(let plane):
      return Plane(
        normal: plane.normal, offset: plane.offset,
        materialIndex: plane.materialIndex)
    case .triangle(let triangle):
      return Self.triangle(triangle)
    case .mesh(let mesh):
      let key = MeshKey(
        storage: mesh.storage.identity, material: mesh.materialIndex)
      if mesh.materialIndices.isEmpty, let made = meshes[key] { return made }
      let made = TriangleMesh(mesh.map(Self.triangle))
      if mesh.materialIndices.isEmpty { meshes[key] = made }
      return made
    case .group(let inner):
      return group(inner)
    case .transform(let transform):
      return self.object(transform.object).flatMap {
        Transform(matrix: transform.matrix, object: $0)
      }
    case .shape(let shape):
      return shape.object
    }
  }

  static func triangle(_ triangle: SceneDescription.Triangle<Double>)
    -> Triangle
  {
    var result = Triangle(
      triangle.v0, triangle.v1, triangle.v2,
      materialIndex: triangle.materialIndex)
    if let normals = triangle.vertexNormals {
      result.normals = (normals.n0, normals.n1, normals.n2)
    }
    if let uv = triangle.textureCoordinates {
      result.textureCoordinates = (uv.t0, uv.t1, uv.t2)
    }
    return result
  }
}
