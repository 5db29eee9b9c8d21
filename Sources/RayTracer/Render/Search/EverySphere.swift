/// The flat loop: every sphere, in scene order.
struct EverySphere: NearestSphereSearch {
  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    var nearest = NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest>(
      before: .infinity)
    scene.spheres.withUnsafeBufferPointer { records in
      for index in records.indices {
        nearest.test(.sphere(index)) {
          Kernel.intersect(records[index], ray, before: $0)
        }
      }
    }
    return nearest
  }
}
