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
/// Every larger payload is boxed, so that an entry is no bigger than a
/// sphere (48 bytes in Double): triangles, a mesh file's triangles (one
/// entry, their arrays: `TriangleMesh`, 88 bytes inline), a shape of
/// one's own, and a transform, which must be, since it holds an object.
/// With the meshes inline, the entries of a million spheres took 84 MiB
/// instead of 46, fresh pages each zeroed by the kernel.
public enum SceneObject<Scalar: RayScalar>: Hashable, Sendable {
  case sphere(Sphere<Scalar>)
  case plane(Plane<Scalar>)
  indirect case triangle(Triangle<Scalar>)
  indirect case mesh(TriangleMesh<Scalar>)
  case group(Group<Scalar>)
  indirect case transform(Transform<Scalar>)
  /// A shape of a kind the scene's readers and the fast engine do not
  /// specialise, hit through its `Hittable` conformance in Double.
  indirect case shape(Shape)
}
