import Geometry

/// A list of objects, nested groups included, hit as one.
public struct Group<Scalar: RayScalar>: Hashable, Sendable {
  public var objects: [SceneObject<Scalar>]

  public init(_ objects: [SceneObject<Scalar>] = []) {
    self.objects = objects
  }
}

/// One entry of a group: an enum rather than an existential, so that
/// whatever walks a scene dispatches statically.
///
/// Spheres and planes are stored inline: boxing each one cost a heap
/// allocation per object, a fifth of the parse of a million spheres.
/// Larger payloads are boxed, so an entry is a sphere and its tag (48
/// bytes in Double; a mesh inline made it 88, and 10⁶ spheres' entries
/// 84 MiB rather than 46); a transform must be, since it holds an object.
public enum SceneObject<Scalar: RayScalar>: Hashable, Sendable {
  case sphere(Sphere<Scalar>)
  case plane(Plane<Scalar>)
  indirect case triangle(Triangle<Scalar>)
  indirect case mesh(TriangleMesh<Scalar>)
  case group(Group<Scalar>)
  indirect case transform(Transform<Scalar>)
  /// A shape of a kind the scene's readers and the compiled engine do not
  /// specialise, hit through its `Hittable` conformance in Double.
  indirect case shape(Shape)
}
