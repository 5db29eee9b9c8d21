import Geometry

/// The scene's bounding volume hierarchy of spheres: the four-wide tree
/// where it can answer for the ray, else the binary one.
///
/// - Precondition: the scene has a hierarchy (`CompiledScene.usesHierarchy`).
struct SphereHierarchy: NearestSphereSearch {
  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    var nearest = NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest>(
      before: .infinity)
    guard let hierarchy = scene.hierarchy else {
      preconditionFailure("the scene has no sphere hierarchy")
    }
    scene.spheres.withUnsafeBufferPointer { records in
      let leaves = SphereLeaves<Kernel>(records: records, ray: ray)
      if let hit = hierarchy.nearest(
        ray, before: nearest.t, leaves: leaves, wide: scene.wideHierarchy)
      {
        nearest.test(.sphere(hit.index)) { _ in hit.t }
      }
    }
    return nearest
  }
}
