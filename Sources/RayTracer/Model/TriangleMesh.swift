/// The triangles of one mesh file (the course's `TriangleMesh { obj_file … }`),
/// hit as a group of them.
///
/// Kept side by side in one array rather than as one group entry each: a
/// group's triangle entries are boxed, a heap allocation apiece, and for a
/// mesh of millions the boxes, their entries and the page faults of both
/// were most of reading it. The array is shared, not copied, when an
/// untransformed mesh is the scene's only triangles (`Group.flattened`).
public struct TriangleMesh<Scalar: RayScalar>: Hashable, Sendable {
  public var triangles: [Triangle<Scalar>]

  public init(_ triangles: [Triangle<Scalar>]) {
    self.triangles = triangles
  }
}

extension TriangleMesh: Intersectable {
  /// The nearest hit among the triangles, as a group's (`nearestHit`): a
  /// tie goes to the earlier triangle.
  public func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    triangles.nearestHit(ray, after: tMin, before: tMax, method: method)
  }

  public func occludes(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Bool {
    triangles.contains { $0.occludes(ray, after: tMin, before: tMax) }
  }
}
