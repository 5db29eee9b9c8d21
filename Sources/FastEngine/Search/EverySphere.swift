import Geometry

/// The flat loop: every sphere, in scene order.
struct EverySphere: NearestSphereSearch {
  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    scene.nearestSphere(ray, among: scene.spheres.indices)
  }

  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>,
    memo: inout Kernel.SphereHitMemo
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    scene.nearestSphere(ray, among: scene.spheres.indices, memo: &memo)
  }
}

extension CompiledScene {
  /// The nearest hit of `ray` among the spheres at `indices`, tested in
  /// the order given (scene order, for `NearestHit`'s tie rule).
  @inline(__always)
  func nearestSphere<Indices: Sequence<Int>>(
    _ ray: CameraRay<Scalar>, among indices: Indices
  ) -> NearestHit<Scalar, Nearest> {
    var memo = Kernel.noMemo
    return nearestSphere(ray, among: indices, memo: &memo)
  }

  /// `nearestSphere(_:among:)`, also keeping in `memo` what the nearest
  /// hit's test computed for its normal (`Kernel.SphereHitMemo`).
  @inline(__always)
  func nearestSphere<Indices: Sequence<Int>>(
    _ ray: CameraRay<Scalar>, among indices: Indices,
    memo: inout Kernel.SphereHitMemo
  ) -> NearestHit<Scalar, Nearest> {
    var nearest = NearestHit<Scalar, Nearest>(before: .infinity)
    var candidate = Kernel.noMemo
    spheres.withUnsafeBufferPointer { records in
      for index in indices {
        if let t = Kernel.intersect(
          records[index], ray, before: nearest.t, memo: &candidate)
        {
          nearest = NearestHit(t, .sphere(index))
          memo = candidate
        }
      }
    }
    return nearest
  }
}
