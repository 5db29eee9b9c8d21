/// What a pixel's nearest hit becomes: its depth, normal and colour, and
/// the colour of a supersampled pixel.
extension Renderer {
  /// Writes a pixel's requested outputs from its nearest hit (nil: none).
  /// `sphereRecord`, when given, is a copy of the record of the sphere the
  /// search found, for the normal if that sphere is still the nearest.
  @inline(__always)
  static func store<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?,
    ray: CameraRay<Kernel.Scalar>, pixel: Int, scene: CompiledScene<Kernel>,
    settings: RenderSettings, targets: Targets<Kernel.Scalar>,
    sphereRecord: Kernel.SphereRecord? = nil
  ) {
    let wantsDepth = targets.wantsDepth
    let wantsNormals = targets.wantsNormals
    let shadeCentre = targets.wantsColor && settings.samples == 1
    guard let hit else {
      if wantsDepth { targets.depth[pixel] = .infinity }
      if wantsNormals { targets.setNormal(.zero, at: pixel) }
      if shadeCentre { targets.setColor(scene.background, at: pixel) }
      return
    }
    if wantsDepth { targets.depth[pixel] = hit.t * scene.lengthScale }
    guard wantsNormals || shadeCentre else { return }
    let normal: Vector3<Kernel.Scalar>
    if case .sphere = hit.what, let sphereRecord {
      normal = Kernel.normal(sphereRecord, ray, t: hit.t)
    } else {
      normal = scene.normal(of: hit.what, ray, t: hit.t)
    }
    if wantsNormals { targets.setNormal(normal, at: pixel) }
    if shadeCentre {
      targets.setColor(
        shade(
          hit, ray: ray, normal: normal, scene: scene,
          attenuate: settings.style == .mit), at: pixel)
    }
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
        guard let hit = scene.nearest(ray, by: search) else {
          sum += scene.background
          continue
        }
        let normal = scene.normal(of: hit.what, ray, t: hit.t)
        sum += shade(
          hit, ray: ray, normal: normal, scene: scene,
          attenuate: settings.style == .mit)
      }
    }
    return sum / S(samples.count)
  }
}
