import SceneDescription

/// The kinds of object the course adds to the ones the readers know
/// (Sphere, Plane, Triangle, TriangleMesh, Group, Transform): a new shape is
/// named here once, with its fields, and both scene formats read it
/// (docs/ADDING-A-SHAPE.md). For a disc:
///
///     ShapeKind(
///       name: "Disc",
///       fields: [("center", 3), ("normal", 3), ("radius", 1)]
///     ) { values, material in
///       .success(Disc(center: Vector3(values["center"]!), …))
///     }
public enum CourseShapes {
  public static let all: [ShapeKind] = []
}
