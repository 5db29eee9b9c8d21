import FastKernels
import Geometry
import SceneDescription
import PlatformSupport

/// The pixel loop of `ScreenTiles`: a tile's rays generated together, then
/// each listed sphere tested against the rays of its box's pixels only,
/// then each pixel's search finished past the spheres. For a supersampled
/// render the same is done once per sample, every pixel's k-th sample
/// together (`renderProjectedSamples`).
extension Renderer {
  /// Renders one tile of `ScreenTiles`: each sphere tested only against the
  /// rays of its box's pixels, in scene order with the flat loop's strict
  /// `<`, then each pixel's search continued past the spheres.
  static func renderProjectedTile<Kernel: IntersectionKernel, R: RayScalar>(
    _ entries: ArraySlice<ScreenTiles<Kernel>.Entry>,
    _ triangleEntries: ArraySlice<ScreenTiles<Kernel>.TriangleEntry>,
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
            let y: R = settings.screen.y(row: row)
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
          finishSearches(
            entries, triangleEntries, rows: rows.count,
            columns: tileColumns.count, scene: scene, rays: rays,
            nearestT: nearestT, nearestEntry: nearestEntry
          ) { slot, hit, entry, weights in
            let row = rows.lowerBound + slot / ScreenTiles<Kernel>.tileWidth
            let column =
              tileColumns.lowerBound + slot % ScreenTiles<Kernel>.tileWidth
            store(
              hit, ray: rays[slot], pixel: row * settings.width + column,
              scene: scene, settings: settings, targets: targets,
              sphereRecord: entry?.record, triangleWeights: weights)
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

  /// One entry's triangle tested against the rays of its box's pixels:
  /// each ray first through the triangle's edge planes (`sides`, when
  /// given), then by the watertight test or, for a large triangle, its
  /// plane. With `sharedFrame`, when every prepared ray shares one frame
  /// (`WatertightRay.sharesFrame`), the triangle is carried into it once
  /// (`PermutedTriangle`) and each ray's test starts from there, with the
  /// same bits. A function of its own, not inlined into `finishSearches`:
  /// the 10³-triangle mesh 3–8 % faster on one thread so.
  @inline(never)
  static func testTriangle<Kernel: IntersectionKernel>(
    _ entry: ScreenTiles<Kernel>.TriangleEntry, _ index: Int,
    _ records: UnsafeBufferPointer<TriangleRecord<Kernel.Scalar>>,
    plane: LargeTrianglePlane<Kernel.Scalar>?,
    exact: TrianglePlane.Exact<Kernel.Scalar>?,
    sides: TriangleEdgePlanes<Kernel.Scalar>?,
    sharedFrame: Bool,
    rays: UnsafeMutableBufferPointer<CameraRay<Kernel.Scalar>>,
    prepared: UnsafeMutableBufferPointer<WatertightRay<Kernel.Scalar>>,
    searches: UnsafeMutableBufferPointer<
      NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest>
    >,
    weights: UnsafeMutableBufferPointer<TriangleWeights<Kernel.Scalar>>
  ) {
    let tileWidth = ScreenTiles<Kernel>.tileWidth
    let record = records[index]
    // Each ray of the box that the edge planes do not exclude.
    @inline(__always)
    func eachRay(_ body: (Int) -> Void) {
      for row in Int(entry.firstRow)...Int(entry.lastRow) {
        for column in Int(entry.firstColumn)...Int(entry.lastColumn) {
          let slot = row * tileWidth + column
          if let sides, sides.excludes(rays[slot].direction) {
            continue
          }
          body(slot)
        }
      }
    }
    // Two loops rather than a choice per ray: one loop choosing made the
    // 5·10⁶-triangle mesh 8 % slower.
    if sharedFrame && plane == nil {
      let permuted = PermutedTriangle(
        prepared[Int(entry.firstRow) * tileWidth + Int(entry.firstColumn)],
        record.v0, record.v1, record.v2)
      // The triangles whose t comes from their exact planes in a loop of
      // their own, so that the others' loop is the one it was.
      if let exact {
        eachRay { slot in
          searches[slot].test(.triangle(index)) {
            guard
              let hit = TriangleIntersection.intersect(
                prepared[slot], permuted, plane: exact, after: 0, before: $0)
            else { return nil }
            weights[slot] = TriangleWeights(u: hit.u, v: hit.v, w: hit.w)
            return hit.t
          }
        }
        return
      }
      eachRay { slot in
        searches[slot].test(.triangle(index)) {
          guard
            let hit = TriangleIntersection.intersect(
              prepared[slot], permuted, after: 0, before: $0)
          else { return nil }
          weights[slot] = TriangleWeights(u: hit.u, v: hit.v, w: hit.w)
          return hit.t
        }
      }
      return
    }
    eachRay { slot in
      searches[slot].test(.triangle(index)) {
        if let plane {
          return TriangleRecord.t(
            prepared[slot], records.baseAddress! + index,
            plane: plane, before: $0)
        }
        let found =
          if let exact {
            record.intersect(prepared[slot], plane: exact, before: $0)
          } else {
            record.intersect(prepared[slot], before: $0)
          }
        guard let hit = found else { return nil }
        weights[slot] = TriangleWeights(u: hit.u, v: hit.v, w: hit.w)
        return hit.t
      }
    }
  }

  /// Each pixel's search of a tile finished after its spheres
  /// (`testEntries`): planes, then the projected triangles of
  /// `triangleEntries`, the large ones included (each tested against the
  /// rays of its box's pixels, in order with the flat loop's strict `<`),
  /// then the ellipsoids; or, when the scene does not project its triangles,
  /// the scene's own search after the spheres. `body` gets each slot, its
  /// nearest hit, the sphere entry found, if any, and for a hit on an
  /// ordinary projected triangle the barycentric weights its test gave.
  @inline(__always)
  static func finishSearches<Kernel: IntersectionKernel>(
    _ entries: ArraySlice<ScreenTiles<Kernel>.Entry>,
    _ triangleEntries: ArraySlice<ScreenTiles<Kernel>.TriangleEntry>,
    rows: Int, columns: Int, scene: CompiledScene<Kernel>,
    rays: UnsafeMutableBufferPointer<CameraRay<Kernel.Scalar>>,
    nearestT: UnsafeMutableBufferPointer<Kernel.Scalar>,
    nearestEntry: UnsafeMutableBufferPointer<Int32>,
    _ body:
      (
        Int, (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?,
        ScreenTiles<Kernel>.Entry?, TriangleWeights<Kernel.Scalar>?
      ) -> Void
  ) {
    typealias S = Kernel.Scalar
    typealias Search = NearestHit<S, CompiledScene<Kernel>.Nearest>
    let tileWidth = ScreenTiles<Kernel>.tileWidth
    func sphere(_ slot: Int) -> ScreenTiles<Kernel>.Entry? {
      let position = Int(nearestEntry[slot])
      return position >= 0 ? entries[entries.startIndex + position] : nil
    }
    guard scene.projectsTriangles else {
      // Spheres and planes only: the planes tested here, not through
      // `scene.nearest`, whose copy of each ray for the searches after
      // them made the course scene's render 1.3 times slower, and the
      // spheres' rows 1.15 times (docs/PERFORMANCE.md, "The sphere
      // rows").
      if scene.holdsOnly([.sphere, .plane]) {
        for row in 0..<rows {
          for column in 0..<columns {
            let slot = row * tileWidth + column
            let entry = sphere(slot)
            var search = Search(
              nearestT[slot], entry.map { .sphere(Int($0.sphere)) })
            scene.testPlanes(rays[slot], &search)
            body(slot, search.hit, entry, nil)
          }
        }
        return
      }
      for row in 0..<rows {
        for column in 0..<columns {
          let slot = row * tileWidth + column
          let entry = sphere(slot)
          body(
            slot,
            scene.nearest(
              rays[slot],
              after: NearestHit(
                nearestT[slot], entry.map { .sphere(Int($0.sphere)) })),
            entry, nil)
        }
      }
      return
    }
    let capacity = tileWidth * ScreenTiles<Kernel>.tileHeight
    withUnsafeTemporaryAllocation(of: Search.self, capacity: capacity) {
      searches in
      withUnsafeTemporaryAllocation(
        of: WatertightRay<S>.self, capacity: capacity
      ) { prepared in
        // Per slot, the weights of the last ordinary triangle test that
        // gave a hit. Every hit a test returns is strictly nearer than the
        // best and becomes it, so when the nearest hit is an ordinary
        // triangle, the last such test was its own. (A large triangle takes
        // t from its plane and gives no weights.)
        withUnsafeTemporaryAllocation(
          of: TriangleWeights<S>.self, capacity: capacity
        ) { weights in
          // The rays are prepared for the watertight test only inside the
          // union of the triangles' boxes: no other slot is tested (the
          // three divisions of a tile without triangles are saved).
          var covered = (
            firstRow: Int.max, lastRow: Int.min, firstColumn: Int.max,
            lastColumn: Int.min
          )
          for entry in triangleEntries {
            covered.firstRow = min(covered.firstRow, Int(entry.firstRow))
            covered.lastRow = max(covered.lastRow, Int(entry.lastRow))
            covered.firstColumn = min(
              covered.firstColumn, Int(entry.firstColumn))
            covered.lastColumn = max(covered.lastColumn, Int(entry.lastColumn))
          }
          for row in 0..<rows {
            for column in 0..<columns {
              let slot = row * tileWidth + column
              let ray = rays[slot]
              var search = Search(
                nearestT[slot], sphere(slot).map { .sphere(Int($0.sphere)) })
              scene.testPlanes(ray, &search)
              (searches.baseAddress! + slot).initialize(to: search)
            }
          }
          // Whether every prepared ray shares the first one's frame
          // (`sharesFrame`), as a tile's camera rays do unless it straddles
          // a change of the direction's largest axis: then each ordinary
          // triangle is carried into that frame once, not once per ray.
          var sharedFrame = false
          if covered.firstRow <= covered.lastRow {
            let first = covered.firstRow * tileWidth + covered.firstColumn
            var shared = true
            for row in covered.firstRow...covered.lastRow {
              for column in covered.firstColumn...covered.lastColumn {
                let slot = row * tileWidth + column
                let ray = rays[slot]
                (prepared.baseAddress! + slot).initialize(
                  to: WatertightRay(
                    Ray(origin: ray.origin, direction: ray.direction)))
                shared =
                  shared && prepared[slot].sharesFrame(with: prepared[first])
              }
            }
            sharedFrame = shared
          }
          // The large triangles (`TrianglePlane`) come after the ordinary
          // ones in index order, as in the search without tiles, and take t
          // from their planes.
          let ordinary = scene.ordinaryTriangleCount
          // Not in Float, whose edge-plane margins (256 ε of the corners'
          // distances squared) are wider than most triangles a few pixels
          // across (the 10⁵-triangle mesh 12 % slower with them, no Float
          // render faster).
          let edgePlanes = S.significandBitCount > Float.significandBitCount
          scene.triangles.withUnsafeBufferPointer { records in
            for entry in triangleEntries {
              let index = Int(entry.triangle)
              let record = records[index]
              let plane =
                index < ordinary ? nil : scene.trianglePlanes[index - ordinary]
              // An ordinary triangle over more than a few pixels first
              // looks at each ray through its edges' planes.
              let sides =
                edgePlanes && plane == nil
                  && (Int(entry.lastColumn) - Int(entry.firstColumn)
                    + Int(entry.lastRow) - Int(entry.firstRow)) >= 2
                ? TriangleEdgePlanes(
                  record.v0, record.v1, record.v2, origin: scene.rayOrigin)
                : nil
              testTriangle(
                entry, index, records, plane: plane,
                exact: scene.exactPlane(ofTriangle: index), sides: sides,
                sharedFrame: sharedFrame, rays: rays,
                prepared: prepared, searches: searches, weights: weights)
            }
          }
          for row in 0..<rows {
            for column in 0..<columns {
              let slot = row * tileWidth + column
              scene.testEllipsoids(rays[slot], &searches[slot])
              let hit = searches[slot].hit
              var found: TriangleWeights<S>?
              if case .triangle(let index)? = hit?.what, index < ordinary {
                found = weights[slot]
              }
              body(slot, hit, sphere(slot), found)
            }
          }
        }
      }
    }
  }
}
