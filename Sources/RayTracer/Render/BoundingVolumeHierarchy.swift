/// Placeholder until the BVH lands: a flat list (no hierarchy) that keeps
/// the interface the render loop uses.
public struct BoundingVolumeHierarchy<Scalar: RayScalar>: Sendable {
  public static var defaultThreshold: Int { Int.max }
  let order: [Int32]

  init(centers: [Vector3<Scalar>], radii: [Scalar]) {
    order = (0..<Int32(centers.count)).map { $0 }
  }

  func nearest<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Scalar>, before tMax: Scalar,
    records: UnsafeBufferPointer<Kernel.SphereRecord>, kernel: Kernel.Type
  ) -> (t: Scalar, index: Int)? where Kernel.Scalar == Scalar {
    var tBest = tMax
    var best: Int?
    for index in records.indices {
      if let t = Kernel.intersect(records[index], ray, before: tBest) {
        tBest = t
        best = index
      }
    }
    return best.map { (tBest, $0) }
  }
}
