import Geometry

/// A supersampled pixel: what each of its samples gives, and the means the
/// outputs take (`RenderSettings.samples`, `samplesAllOutputs`).
extension Renderer {
  /// One sample of a supersampled pixel: its depth (nil for a miss); its
  /// normal when `normals` or `shade` asks (zero for a miss); its colour
  /// when `shade` asks (the background for a miss). From a layer when one
  /// has a nearer hit, as in `store`.
  @inline(__always)
  static func sample<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?,
    ray: CameraRay<Kernel.Scalar>, scene: CompiledScene<Kernel>,
    sphereRecord: Kernel.SphereRecord? = nil,
    triangleWeights: TriangleWeights<Kernel.Scalar>? = nil,
    normals: Bool, shade: Bool, attenuate: Bool
  ) -> Sample<Kernel.Scalar> {
    if !scene.layers.isEmpty,
      let (layer, layerHit, layerRay) = scene.nearerInLayers(ray, than: hit)
    {
      let layerScene = scene.layers[layer]
      let normal =
        normals || shade
        ? layerScene.normal(of: layerHit.what, layerRay, t: layerHit.t)
        : .zero
      return Sample(
        depth: layerHit.t * layerScene.lengthScale, normal: normal,
        color: shade
          ? self.shade(
            layerHit, ray: layerRay, normal: normal, scene: layerScene,
            attenuate: attenuate) : .zero)
    }
    guard let hit else {
      return Sample(depth: nil, normal: .zero, color: scene.background)
    }
    let normal =
      normals || shade
      ? self.normal(
        of: hit, ray: ray, scene: scene, sphereRecord: sphereRecord,
        triangleWeights: triangleWeights) : .zero
    return Sample(
      depth: hit.t * scene.lengthScale, normal: normal,
      color: shade
        ? self.shade(
          hit, ray: ray, normal: normal, scene: scene, attenuate: attenuate)
        : .zero)
  }

  /// Supersamples pixel (`column`, `row`) (`PixelSamples`), its samples'
  /// spheres found by `search`, which must answer for every ray of the
  /// pixel's filter support: its colour when shaded, and its depth and
  /// normal too with `samplesAllOutputs`.
  @inline(__always)
  static func supersample<
    Kernel: IntersectionKernel, R: RayScalar, Search: NearestSphereSearch
  >(
    column: Int, row: Int, by search: Search, scene: CompiledScene<Kernel>,
    camera: PerspectiveCamera<R>, settings: RenderSettings,
    targets: Targets<Kernel.Scalar>
  ) {
    typealias S = Kernel.Scalar
    let all = settings.supersamplesAll
    let (normals, shade) = (all && targets.wantsNormals, targets.wantsColor)
    var sums = SampleSums<S>()
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
        sums.add(
          sample(
            scene.nearest(ray, by: search), ray: ray, scene: scene,
            normals: normals, shade: shade,
            attenuate: settings.attenuatesLights), all: all)
      }
    }
    sums.store(
      samples: samples.count, at: row * settings.width + column, in: targets,
      all: all)
  }
}

/// What one sample of a pixel gives its outputs (`Renderer.sample`).
struct Sample<S: RayScalar> {
  /// The hit's distance in the scene's lengths; nil for a miss.
  var depth: S?
  var normal: Vector3<S>
  var color: RGB<S>
}

/// A supersampled pixel's sums over its samples, in their order: the
/// colours and, when every output is sampled, the depths of the samples
/// that hit and the normals (a miss adds zero).
struct SampleSums<S: RayScalar> {
  var color = RGB<S>.zero
  var normal = Vector3<S>.zero
  var depth: S = 0
  var hits = 0

  @inline(__always)
  mutating func add(_ sample: Sample<S>, all: Bool) {
    color += sample.color
    guard all, let depth = sample.depth else { return }
    addHit(depth: depth, normal: sample.normal)
  }

  /// A sample that hit, for depth and normal.
  @inline(__always)
  mutating func addHit(depth: S, normal: Vector3<S>) {
    self.depth += depth
    self.normal += normal
    hits += 1
  }

  /// Writes the means of `samples` samples: the colour when it is wanted,
  /// and depth and normal when `all` (depth ∞ when no sample hit).
  @inline(__always)
  func store(
    samples: Int, at pixel: Int, in targets: Renderer.Targets<S>, all: Bool
  ) {
    let count = S(samples)
    if targets.wantsColor { targets.setColor(color / count, at: pixel) }
    guard all else { return }
    if targets.wantsDepth {
      targets.depth[pixel] = hits > 0 ? depth / S(hits) : .infinity
    }
    if targets.wantsNormals { targets.setNormal(normal / count, at: pixel) }
  }
}
