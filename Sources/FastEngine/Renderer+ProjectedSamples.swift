import Geometry
import SceneDescription
import PlatformSupport

/// The pixel loop of `ScreenTiles` for a supersampled render: the tile's
/// searches (`renderProjectedTile`'s) done once per sample, every pixel's
/// k-th sample together, then the samples shaded in loops of their own
/// (and their depths and normals summed, when every output is sampled).
extension Renderer {
  /// The supersampled outputs of one tile (`SampleSums.store`): each pixel's
  /// samples (`PixelSamples`) searched as `renderProjectedTile` searches
  /// its centre ray, the k-th sample of every pixel at a time, with boxes
  /// widened by the filter's reach (`ScreenTiles.init`). Each pixel's
  /// values are summed in its samples' order, so the images are the ones
  /// `supersample` gives, bit for bit.
  static func renderProjectedSamples<Kernel: IntersectionKernel, R: RayScalar>(
    _ entries: ArraySlice<ScreenTiles<Kernel>.Entry>,
    _ triangleEntries: ArraySlice<ScreenTiles<Kernel>.TriangleEntry>,
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
    let attenuate = settings.attenuatesLights
    let all = settings.supersamplesAll
    let (wantsNormals, shade) = (
      all && targets.wantsNormals, targets.wantsColor
    )
    func slot(_ row: Int, _ column: Int) -> Int {
      (row - rows.lowerBound) * tileWidth + column - tileColumns.lowerBound
    }
    withUnsafeTemporaryAllocation(of: PixelSamples<R>.self, capacity: capacity)
    { samples in
      withUnsafeTemporaryAllocation(of: SampleSums<S>.self, capacity: capacity)
      {
        sums in
        withUnsafeTemporaryAllocation(of: CameraRay<S>.self, capacity: capacity)
        { rays in
          withUnsafeTemporaryAllocation(of: S.self, capacity: capacity) {
            nearestT in
            withUnsafeTemporaryAllocation(of: Int32.self, capacity: capacity) {
              nearestEntry in
              withUnsafeTemporaryAllocation(
                of: FoundHit<Kernel>.self, capacity: capacity
              ) {
                hits in
                withUnsafeTemporaryAllocation(
                  of: Vector3<R>.self, capacity: capacity
                ) { points in
                  withUnsafeTemporaryAllocation(
                    of: Vector3<S>.self, capacity: capacity
                  ) { normals in
                    var count = 0
                    for row in rows {
                      for column in tileColumns {
                        let pixel = PixelSamples(
                          column: column, row: row, camera: camera,
                          settings: settings)
                        count = pixel.count
                        (samples.baseAddress! + slot(row, column)).initialize(
                          to: pixel)
                        (sums.baseAddress! + slot(row, column)).initialize(
                          to: SampleSums())
                      }
                    }
                    for _ in 0..<count {
                      // The samples' points, then their unit directions in a
                      // loop of their own, so that one sample's square root and
                      // divisions overlap the next one's.
                      for row in rows {
                        for column in tileColumns {
                          let slot = slot(row, column)
                          (points.baseAddress! + slot).initialize(
                            to: samples[slot].nextThroughScreen()!)
                        }
                      }
                      for row in rows {
                        for column in tileColumns {
                          let slot = slot(row, column)
                          (rays.baseAddress! + slot).initialize(
                            to: CameraRay(
                              origin: scene.rayOrigin,
                              direction: Vector3<S>(
                                points[slot].normalizedByReciprocal())))
                          (nearestT.baseAddress! + slot).initialize(
                            to: .infinity)
                          (nearestEntry.baseAddress! + slot).initialize(to: -1)
                        }
                      }
                      testEntries(
                        entries, rays: rays, nearestT: nearestT,
                        nearestEntry: nearestEntry)
                      finishSearches(
                        entries, triangleEntries, rows: rows.count,
                        columns: tileColumns.count, scene: scene, rays: rays,
                        nearestT: nearestT, nearestEntry: nearestEntry
                      ) { slot, hit, entry, weights in
                        (hits.baseAddress! + slot).initialize(
                          to: FoundHit(
                            hit: hit, record: entry?.record, weights: weights))
                      }
                      // Shaded after every search of the tile, in loops of
                      // their own: arch at 16 samples 20 % faster than
                      // shading each sample inside the search loop, the
                      // 10³-triangle mesh 15 %; and the normals before the
                      // colours, each loop's square roots and divisions
                      // overlapping from one sample to the next (the course
                      // scene 4–7 %, 10⁴ spheres 5 %; docs/PERFORMANCE.md,
                      // "Shading"). A scene with layers goes through
                      // `sampleColor`, which looks for a nearer hit in them
                      // first.
                      if scene.layers.isEmpty {
                        if shade || wantsNormals {
                          for row in rows {
                            for column in tileColumns {
                              let slot = slot(row, column)
                              let found = hits[slot]
                              guard let hit = found.hit else { continue }
                              (normals.baseAddress! + slot).initialize(
                                to: normal(
                                  of: hit, ray: rays[slot], scene: scene,
                                  sphereRecord: found.record,
                                  triangleWeights: found.weights))
                            }
                          }
                        }
                        if shade {
                          for row in rows {
                            for column in tileColumns {
                              let slot = slot(row, column)
                              guard let hit = hits[slot].hit else {
                                sums[slot].color += scene.background
                                continue
                              }
                              sums[slot].color += self.shade(
                                hit, ray: rays[slot], normal: normals[slot],
                                scene: scene, attenuate: attenuate)
                            }
                          }
                        }
                        if all {
                          for row in rows {
                            for column in tileColumns {
                              let slot = slot(row, column)
                              guard let hit = hits[slot].hit else { continue }
                              sums[slot].addHit(
                                depth: hit.t * scene.lengthScale,
                                normal: wantsNormals ? normals[slot] : .zero)
                            }
                          }
                        }
                      } else {
                        for row in rows {
                          for column in tileColumns {
                            let slot = slot(row, column)
                            let found = hits[slot]
                            sums[slot].add(
                              sample(
                                found.hit, ray: rays[slot], scene: scene,
                                sphereRecord: found.record,
                                triangleWeights: found.weights,
                                normals: wantsNormals, shade: shade,
                                attenuate: attenuate), all: all)
                          }
                        }
                      }
                    }
                    for row in rows {
                      for column in tileColumns {
                        sums[slot(row, column)].store(
                          samples: count, at: row * settings.width + column,
                          in: targets, all: all)
                      }
                    }
                  }
                }
              }
            }
          }
        }
      }
    }
  }
}

/// What a sample's search found, kept until the tile's samples are shaded
/// together: the nearest hit, the record of the sphere entry found (if any;
/// a sphere found is the entry's, since only other kinds are searched
/// after the entries) and an ordinary triangle's weights.
struct FoundHit<Kernel: IntersectionKernel> {
  var hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?
  var record: Kernel.SphereRecord?
  var weights: TriangleWeights<Kernel.Scalar>?
}
