import Geometry

/// The triangles of a mesh file (the course's `TriangleMesh`), hit through
/// a hierarchy of boxes built once (`BoxHierarchy`), as the course's mesh
/// is hit through its octree: a ray tests only the triangles whose boxes
/// it meets.
public struct TriangleMesh: Hittable {
  public let triangles: [Triangle]
  private let hierarchy: BoxHierarchy

  public init(_ triangles: [Triangle]) {
    self.triangles = triangles
    hierarchy = BoxHierarchy(
      boxes: triangles.map { BoundingBox(around: $0.a, $0.b, $0.c) })
  }

  /// The nearest hit of the triangles: each triangle the hierarchy hands
  /// over is asked for a hit before the nearest so far.
  public func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    // BEGIN SOLUTION week 5: triangles and meshes — the nearest hit of the
    //   triangles the hierarchy hands over, each asked for a hit before the
    //   nearest so far
    var nearest: Hit<Double>?
    hierarchy.forEachCandidate(ray, before: { nearest?.t ?? tMax }) {
      index in
      if let hit = triangles[index].intersect(
        ray, after: tMin, before: nearest?.t ?? tMax)
      {
        nearest = hit
      }
    }
    return nearest
    // END SOLUTION
  }

  public var boundingBox: BoundingBox? { hierarchy.bounds }
}
