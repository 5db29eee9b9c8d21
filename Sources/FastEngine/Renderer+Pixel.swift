import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// What a pixel's nearest hit becomes: its depth, normal and colour, and
/// the colour of a supersampled pixel.
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

  /// One sample's colour: the background for a miss, else the hit shaded
  /// (from a layer, when one has a nearer hit, as in `store`).
  @inline(__always)
  static func sampleColor<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?,
    ray: CameraRay<Kernel.Scalar>, scene: CompiledScene<Kernel>,
    sphereRecord: Kernel.SphereRecord? = nil,
    triangleWeights: TriangleWeights<Kernel.Scalar>? = nil, attenuate: Bool
  ) -> RGB<Kernel.Scalar> {
    if !scene.layers.isEmpty,
      let (layer, layerHit, layerRay) = scene.nearerInLayers(ray, than: hit)
    {
      let layerScene = scene.layers[layer]
      return shade(
        layerHit, ray: layerRay,
        normal: layerScene.normal(of: layerHit.what, layerRay, t: layerHit.t),
        scene: layerScene, attenuate: attenuate)
    }
    guard let hit else { return scene.background }
    return shade(
      hit, ray: ray,
      normal: normal(
        of: hit, ray: ray, scene: scene, sphereRecord: sphereRecord,
        triangleWeights: triangleWeights),
      scene: scene, attenuate: attenuate)
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

  /// The pixel's colour: the mean of its samples' (`PixelSamples`), their
  /// spheres found by `search`, which must answer for every ray of the
  /// pixel's filter support.
  @inline(__always)
  static func supersampledColor<
    Kernel: IntersectionKernel, R: RayScalar, Search: NearestSphereSearch
  >(
    column: Int, row: Int, by search: Search, scene: CompiledScene<Kernel>,
    camera: PerspectiveCamera<R>,
    settings: RenderSettings
  ) -> RGB<Kernel.Scalar> {
    typealias S = Kernel.Scalar
    var sum = RGB<S>.zero
    var samples = PixelSamples(
      column: column, row: row, camera: camera, settings: settings)
    // The directions first, as for a tile's centre rays (`renderRow`): the
    // square roots and divisions of one sample overlap the next's instead
    // of waiting behind each search. The colours are summed in the same
    // order either way.
    withUnsafeTemporaryAllocation(of: Vector3<S>.self, capacity: samples.count)
    { directions in
      var count = 0
      while let sample = samples.next() {
        (directions.baseAddress! + count).initialize(to: Vector3<S>(sample))
        count += 1
      }
      for direction in directions[0..<count] {
        let ray = CameraRay(origin: scene.rayOrigin, direction: direction)
        sum += sampleColor(
          scene.nearest(ray, by: search), ray: ray, scene: scene,
          attenuate: settings.attenuatesLights)
      }
    }
    return sum / S(samples.count)
  }
}
