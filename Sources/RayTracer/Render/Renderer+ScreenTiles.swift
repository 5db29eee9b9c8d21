/// The pixel loop of `ScreenTiles`: a tile's rays generated together, then
/// each listed sphere tested against the rays of its box's pixels only,
/// then each pixel's search finished past the spheres. For a supersampled
/// render the same is done once per sample, every pixel's k-th sample
/// together.
extension Renderer {
  /// Renders one tile of `ScreenTiles`: each sphere tested only against the
  /// rays of its box's pixels, in scene order with the flat loop's strict
  /// `<`, then each pixel's search continued past the spheres.
  static func renderProjectedTile<Kernel: IntersectionKernel, R: RayScalar>(
    _ entries: ArraySlice<ScreenTiles<Kernel>.Entry>,
    columns tileColumns: Range<Int>, rows: Range<Int>,
    _ columns: UnsafeBufferPointer<R>, _ scene: CompiledScene<Kernel>,
    _ camera: PerspectiveCamera<R>, _ settings: RenderSettings,
    _ targets: Targets<Kernel.Scalar>
  ) {
    typealias S = Kernel.Scalar
    let aspect = R(settings.height) / R(settings.width)
    let capacity =
      ScreenTiles<Kernel>.tileWidth * ScreenTiles<Kernel>.tileHeight
    precondition(
      tileColumns.count <= ScreenTiles<Kernel>.tileWidth
        && rows.count <= ScreenTiles<Kernel>.tileHeight)
    withUnsafeTemporaryAllocation(of: CameraRay<S>.self, capacity: capacity) {
      rays in
      withUnsafeTemporaryAllocation(of: S.self, capacity: capacity) {
        nearestT in
        withUnsafeTemporaryAllocation(of: Int32.self, capacity: capacity) {
          nearestEntry in
          for row in rows {
            let y: R = settings.style.screenY(row: row, height: settings.height)
            let rowBase = camera.rowBase(y: y, aspect: aspect)
            for column in tileColumns {
              let slot =
                (row - rows.lowerBound) * ScreenTiles<Kernel>.tileWidth + column
                - tileColumns.lowerBound
              (rays.baseAddress! + slot).initialize(
                to: CameraRay(
                  origin: scene.rayOrigin,
                  direction: Vector3<S>(
                    camera.rayDirection(x: columns[column], rowBase: rowBase))))
              (nearestT.baseAddress! + slot).initialize(to: .infinity)
              (nearestEntry.baseAddress! + slot).initialize(to: -1)
            }
          }
          testEntries(
            entries, rays: rays, nearestT: nearestT, nearestEntry: nearestEntry)
          for row in rows {
            for column in tileColumns {
              let slot =
                (row - rows.lowerBound) * ScreenTiles<Kernel>.tileWidth + column
                - tileColumns.lowerBound
              let position = Int(nearestEntry[slot])
              let entry =
                position >= 0 ? entries[entries.startIndex + position] : nil
              let hit = scene.nearest(
                rays[slot],
                after: NearestHit(
                  nearestT[slot], entry.map { .sphere(Int($0.sphere)) }))
              store(
                hit, ray: rays[slot], pixel: row * settings.width + column,
                scene: scene,
                settings: settings, targets: targets,
                sphereRecord: entry?.record)
            }
          }
        }
      }
    }
  }

  /// Tests each entry's sphere against the rays of its box's pixels, in
  /// scene order with the flat loop's strict `<`.
  ///
  /// The nearest entry rather than sphere is kept: its copy of the record
  /// is in cache for the normal, the scene's is not. Per pixel, the tie
  /// rule of `NearestHit` in two arrays: entries in scene order, each asked
  /// only for a hit strictly before the pixel's best.
  @inline(__always)
  static func testEntries<Kernel: IntersectionKernel>(
    _ entries: ArraySlice<ScreenTiles<Kernel>.Entry>,
    rays: UnsafeMutableBufferPointer<CameraRay<Kernel.Scalar>>,
    nearestT: UnsafeMutableBufferPointer<Kernel.Scalar>,
    nearestEntry: UnsafeMutableBufferPointer<Int32>
  ) {
    let entryBase = entries.startIndex
    for position in entries.indices {
      let entry = entries[position]
      let record = entry.record
      for row in Int(entry.firstRow)...Int(entry.lastRow) {
        for column in Int(entry.firstColumn)...Int(entry.lastColumn) {
          let slot = row * ScreenTiles<Kernel>.tileWidth + column
          if let t = Kernel.intersect(
            record, rays[slot], before: nearestT[slot])
          {
            nearestT[slot] = t
            nearestEntry[slot] = Int32(truncatingIfNeeded: position - entryBase)
          }
        }
      }
    }
  }

  /// The shaded colours of one tile of a supersampled render: each pixel's
  /// samples (`PixelSamples`) searched as `renderProjectedTile` searches
  /// its centre ray, the k-th sample of every pixel at a time, with boxes
  /// widened by the filter's reach (`ScreenTiles.init`). Each pixel's
  /// colours are summed in its samples' order, so the image is the one
  /// `supersampledColor` gives, bit for bit.
  static func renderProjectedSamples<Kernel: IntersectionKernel, R: RayScalar>(
    _ entries: ArraySlice<ScreenTiles<Kernel>.Entry>,
    columns tileColumns: Range<Int>, rows: Range<Int>,
    _ scene: CompiledScene<Kernel>, _ camera: PerspectiveCamera<R>,
    _ settings: RenderSettings, _ targets: Targets<Kernel.Scalar>
  ) {
    typealias S = Kernel.Scalar
    let tileWidth = ScreenTiles<Kernel>.tileWidth
    let capacity = tileWidth * ScreenTiles<Kernel>.tileHeight
    precondition(
      tileColumns.count <= tileWidth
        && rows.count <= ScreenTiles<Kernel>.tileHeight)
    let attenuate = settings.style == .mit
    func slot(_ row: Int, _ column: Int) -> Int {
      (row - rows.lowerBound) * tileWidth + column - tileColumns.lowerBound
    }
    withUnsafeTemporaryAllocation(of: PixelSamples<R>.self, capacity: capacity)
    { samples in
      withUnsafeTemporaryAllocation(of: RGB<S>.self, capacity: capacity) {
        sums in
        withUnsafeTemporaryAllocation(of: CameraRay<S>.self, capacity: capacity)
        { rays in
          withUnsafeTemporaryAllocation(of: S.self, capacity: capacity) {
            nearestT in
            withUnsafeTemporaryAllocation(of: Int32.self, capacity: capacity) {
              nearestEntry in
              var count = 0
              for row in rows {
                for column in tileColumns {
                  let pixel = PixelSamples(
                    column: column, row: row, camera: camera,
                    settings: settings)
                  count = pixel.count
                  (samples.baseAddress! + slot(row, column)).initialize(
                    to: pixel)
                  (sums.baseAddress! + slot(row, column)).initialize(to: .zero)
                }
              }
              for _ in 0..<count {
                for row in rows {
                  for column in tileColumns {
                    let slot = slot(row, column)
                    let direction = samples[slot].next()!
                    (rays.baseAddress! + slot).initialize(
                      to: CameraRay(
                        origin: scene.rayOrigin,
                        direction: Vector3<S>(direction)))
                    (nearestT.baseAddress! + slot).initialize(to: .infinity)
                    (nearestEntry.baseAddress! + slot).initialize(to: -1)
                  }
                }
                testEntries(
                  entries, rays: rays, nearestT: nearestT,
                  nearestEntry: nearestEntry)
                for row in rows {
                  for column in tileColumns {
                    let slot = slot(row, column)
                    let position = Int(nearestEntry[slot])
                    let entry =
                      position >= 0
                      ? entries[entries.startIndex + position] : nil
                    let ray = rays[slot]
                    guard
                      let hit = scene.nearest(
                        ray,
                        after: NearestHit(
                          nearestT[slot], entry.map { .sphere(Int($0.sphere)) })
                      )
                    else {
                      sums[slot] += scene.background
                      continue
                    }
                    // A sphere found here is the entry's: only planes,
                    // triangles and ellipsoids are searched after it.
                    let normal =
                      if case .sphere = hit.what, let entry {
                        Kernel.normal(entry.record, ray, t: hit.t)
                      } else {
                        scene.normal(of: hit.what, ray, t: hit.t)
                      }
                    sums[slot] += shade(
                      hit, ray: ray, normal: normal, scene: scene,
                      attenuate: attenuate)
                  }
                }
              }
              for row in rows {
                for column in tileColumns {
                  targets.color[row * settings.width + column] =
                    sums[slot(row, column)] / S(count)
                }
              }
            }
          }
        }
      }
    }
  }
}
