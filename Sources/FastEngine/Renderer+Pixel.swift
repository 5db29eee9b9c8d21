import Geometry
import SceneDescription
import PlatformSupport

/// What a pixel's nearest hit becomes: its depth, normal and colour
/// (a supersampled pixel's: `Renderer+Supersampling`).
extension Renderer {
  /// Writes a pixel's requested outputs from its nearest hit (nil: none).
  /// `sphereRecord`, when given, is a copy of the record of the sphere the
  /// search found, for the normal if that sphere is still the nearest;
  /// `sphereMemo` what the sphere search kept from that sphere's test.
  ///
  /// A scene with layers (objects traced at their own scale,
  /// `CompiledScene.layers`) has them searched here, after the scene's own
  /// search, and a nearer hit in one is written from its layer.
  @inline(__always)
  static func store<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?,
    ray: CameraRay<Kernel.Scalar>, pixel: Int, scene: CompiledScene<Kernel>,
    settings: RenderSettings, targets: Targets<Kernel.Scalar>,
    sphereRecord: Kernel.SphereRecord? = nil,
    sphereMemo: Kernel.SphereHitMemo = Kernel.noMemo,
    triangleWeights: TriangleWeights<Kernel.Scalar>? = nil
  ) {
    if !scene.layers.isEmpty,
      let (layer, layerHit, layerRay) = scene.nearerInLayers(ray, than: hit)
    {
      write(
        layerHit, ray: layerRay, pixel: pixel, scene: scene.layers[layer],
        settings: settings, targets: targets)
      return
    }
    write(
      hit, ray: ray, pixel: pixel, scene: scene, settings: settings,
      targets: targets, sphereRecord: sphereRecord, sphereMemo: sphereMemo,
      triangleWeights: triangleWeights)
  }

  /// `store` for a hit of `scene` itself.
  @inline(__always)
  static func write<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?,
    ray: CameraRay<Kernel.Scalar>, pixel: Int, scene: CompiledScene<Kernel>,
    settings: RenderSettings, targets: Targets<Kernel.Scalar>,
    sphereRecord: Kernel.SphereRecord? = nil,
    sphereMemo: Kernel.SphereHitMemo = Kernel.noMemo,
    triangleWeights: TriangleWeights<Kernel.Scalar>? = nil
  ) {
    let wantsDepth = targets.wantsDepth
    let wantsNormals = targets.wantsNormals
    let shadeCentre = targets.wantsColor && !settings.supersamples
    guard let hit else {
      if wantsDepth { targets.depth[pixel] = .infinity }
      if wantsNormals { targets.setNormal(.zero, at: pixel) }
      if shadeCentre { targets.setColor(scene.background, at: pixel) }
      return
    }
    if wantsDepth { targets.depth[pixel] = hit.t * scene.lengthScale }
    guard wantsNormals || shadeCentre else { return }
    let normal = self.normal(
      of: hit, ray: ray, scene: scene, sphereRecord: sphereRecord,
      sphereMemo: sphereMemo, triangleWeights: triangleWeights)
    if wantsNormals { targets.setNormal(normal, at: pixel) }
    if shadeCentre {
      targets.setColor(
        shade(
          hit, ray: ray, normal: normal, scene: scene,
          attenuate: settings.attenuatesLights), at: pixel)
    }
  }

  /// The hit's unit normal, from `sphereRecord` (a copy of the record of
  /// the sphere the search found) when the hit is that sphere, and from
  /// `sphereMemo`, what the sphere search kept of its nearest hit's test.
  @inline(__always)
  static func normal<Kernel: IntersectionKernel>(
    of hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest),
    ray: CameraRay<Kernel.Scalar>, scene: CompiledScene<Kernel>,
    sphereRecord: Kernel.SphereRecord?,
    sphereMemo: Kernel.SphereHitMemo = Kernel.noMemo,
    triangleWeights: TriangleWeights<Kernel.Scalar>? = nil
  ) -> Vector3<Kernel.Scalar> {
    guard case .sphere(let index) = hit.what else {
      return scene.normal(
        of: hit.what, ray, t: hit.t, weights: triangleWeights)
    }
    return Kernel.normal(
      sphereRecord ?? scene.spheres[index], ray, t: hit.t, memo: sphereMemo)
  }

  @inline(__always)
  static func shade<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest),
    ray: CameraRay<Kernel.Scalar>, normal: Vector3<Kernel.Scalar>,
    scene: CompiledScene<Kernel>, attenuate: Bool
  ) -> RGB<Kernel.Scalar> {
    scene.shade(
      hit.what, ray,
      point: scene.eye + ray.direction * (hit.t * scene.lengthScale),
      normal: normal, attenuate: attenuate)
  }
}
