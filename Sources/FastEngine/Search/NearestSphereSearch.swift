
/// How a camera ray's nearest sphere is found: the one interface of the
/// per-ray sphere searches, each in its own file of this folder.
///
/// Every search answers as testing every sphere in scene order would, with
/// `NearestHit`'s tie rule, so the choice among them changes the time a
/// render takes and never its image:
/// - `EverySphere`: the flat loop, for a handful of spheres;
/// - `CulledSpheres` (TileCulling.swift): only the spheres a tile of
///   pixels' rays may hit, for up to a few hundred;
/// - `SphereHierarchy`: the bounding volume hierarchy, for many spheres
///   and for supersampled rays.
/// `ScreenTiles` is the object-order counterpart for single-sample renders
/// of many spheres: each sphere tested only on the pixels its silhouette
/// covers, a whole tile at a time, with the same rule.
///
/// The searches are chosen per render and per tile (`Renderer.renderRows`)
/// and passed as concrete types, so the pixel loop is specialised for each.
protocol NearestSphereSearch {
  /// The nearest sphere hit of `ray` in (0, ∞) among `scene`'s spheres.
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest>

  /// `nearestSphere(_:in:)`, also keeping in `memo` what the nearest
  /// hit's test computed that its normal needs (the flat loops), or
  /// leaving it as it was (the hierarchy).
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>,
    memo: inout Kernel.SphereHitMemo
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest>
}

extension NearestSphereSearch {
  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>,
    memo: inout Kernel.SphereHitMemo
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    nearestSphere(ray, in: scene)
  }
}
