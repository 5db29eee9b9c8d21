/// The flat loop: every sphere, in scene order.
struct EverySphere: NearestSphereSearch {
  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    scene.nearestSphere(ray, among: scene.spheres.indices)
  }
}

extension CompiledScene {
  /// The nearest hit of `ray` among the spheres at `indices`, tested in
  /// the order given (scene order, for `NearestHit`'s tie rule).
  @inline(__always)
  func nearestSphere<Indices: Sequence<Int>>(
    _ ray: CameraRay<Scalar>, among indices: Indices
  ) -> NearestHit<Scalar, Nearest> {
    var nearest = NearestHit<Scalar, Nearest>(before: .infinity)
    spheres.withUnsafeBufferPointer { records in
      for index in indices {
        nearest.test(.sphere(index)) {
          Kernel.intersect(records[index], ray, before: $0)
        }
      }
    }
    return nearest
  }
}
