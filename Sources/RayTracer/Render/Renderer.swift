import Dispatch

/// The per-pixel loop: one camera ray per pixel, nearest hit, then only the
/// quantities the requested outputs need.
public enum Renderer {
  /// Renders `scene` into the buffers `settings.outputs` asks for.
  ///
  /// Rows are handed out to `settings.threads` workers in small batches; every
  /// pixel is computed by the same code whatever the thread count, so the
  /// result is identical bit for bit.
  public static func render<Kernel: IntersectionKernel>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    progress: (@Sendable (Int) -> Void)? = nil
  ) -> RenderBuffers<Kernel.Scalar> {
    renderReportingSearch(scene, settings: settings, progress: progress).buffers
  }

  /// How a render found each pixel's nearest sphere.
  public enum SphereSearch: Sendable, Equatable, CustomStringConvertible {
    case everySphere, culledPerTile, hierarchy, screenTiles
    /// The course engine: every object of the group by the hit protocol.
    case everyObject

    /// In words for `--stats`.
    public var description: String {
      switch self {
      case .everySphere: "testing each"
      case .culledPerTile: "culling per tile"
      case .hierarchy: "BVH"
      case .screenTiles: "screen tiles"
      case .everyObject: "the course engine, every object"
      }
    }
  }

  /// `render`, and how it searched the spheres: a scene compiled for
  /// projection is projected onto screen tiles, or given its hierarchy
  /// when `ScreenTiles` declines it.
  static func renderReportingSearch<Kernel: IntersectionKernel>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    overlapLimit: Int = ScreenTiles<Kernel>.overlapLimit,
    progress: (@Sendable (Int) -> Void)? = nil
  ) -> (buffers: RenderBuffers<Kernel.Scalar>, search: SphereSearch) {
    var scene = scene
    var tiles: ScreenTiles<Kernel>?
    if scene.projectsSpheres && settings.samples == 1 {
      let camera = PerspectiveCamera<Kernel.Scalar>(scene.camera).styled(settings.style)
      tiles = ScreenTiles(scene, camera: camera, settings: settings, overlapLimit: overlapLimit)
    }
    if scene.projectsSpheres && tiles == nil { scene.buildSphereHierarchy() }
    let buffers = render(
      scene, settings: settings, rays: Kernel.Scalar.self, tiles: tiles, progress: progress)
    let search: SphereSearch =
      tiles != nil ? .screenTiles
      : scene.usesHierarchy ? .hierarchy
      : scene.cullsPerTile && settings.samples == 1 ? .culledPerTile : .everySphere
    return (buffers, search)
  }

  /// Renders with camera rays generated in precision `RayPrecision` and then
  /// converted exactly to the kernel's wider type: the reference path, which
  /// intersects the very rays a Float or Double render traced, in Float80.
  public static func render<Kernel: IntersectionKernel, RayPrecision: RayScalar>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    rays: RayPrecision.Type, progress: (@Sendable (Int) -> Void)? = nil
  ) -> RenderBuffers<Kernel.Scalar> {
    render(scene, settings: settings, rays: rays, tiles: nil, progress: progress)
  }

  /// `tiles`, when given, must come from this scene, camera and settings.
  private static func render<Kernel: IntersectionKernel, RayPrecision: RayScalar>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    rays: RayPrecision.Type, tiles: ScreenTiles<Kernel>?, progress: (@Sendable (Int) -> Void)?
  ) -> RenderBuffers<Kernel.Scalar> {
    typealias S = Kernel.Scalar
    let width = settings.width
    let height = settings.height
    let count = width * height
    let outputs = settings.outputs
    let camera = PerspectiveCamera<RayPrecision>(scene.camera).styled(settings.style)
    // Left uninitialised: every pixel of every requested buffer is written
    // exactly once below, so zeroing them first would only cost a pass
    // over memory on one thread.
    var normals: [Vector3<S>] = []
    var color: [RGB<S>] = []
    let depth = uninitializedArray(of: S.self, count: outputs.contains(.depth) ? count : 0) {
      depth in
      normals = uninitializedArray(
        of: Vector3<S>.self, count: outputs.contains(.normals) ? count : 0
      ) { normals in
        color = uninitializedArray(
          of: RGB<S>.self, count: outputs.contains(.shaded) ? count : 0
        ) { color in
          let targets = Targets(depth: depth, normals: normals, color: color)
          // Screen x per column, once per render rather than a division
          // per pixel.
          let columns = (0..<width).map { column -> RayPrecision in
            settings.style.screenX(column: column, width: width)
          }
          columns.withUnsafeBufferPointer { buffer in
            let columns = Shared(buffer)
            forEachRowBatch(
              rows: height, threads: settings.threads, progress: progress
            ) { rows in
              renderRows(rows, columns.value, scene, camera, settings, tiles, targets)
            }
          }
        }
      }
    }
    return RenderBuffers(
      width: width, height: height, depth: depth, normals: normals, color: color)
  }

  /// An array of `count` elements that `initialize` must write, every one.
  private static func uninitializedArray<T>(
    of _: T.Type, count: Int, _ initialize: (UnsafeMutableBufferPointer<T>) -> Void
  ) -> [T] {
    Array(unsafeUninitializedCapacity: count) { buffer, initializedCount in
      Memory.adviseHugePages(UnsafeMutableRawBufferPointer(buffer))
      initialize(buffer)
      initializedCount = count
    }
  }

  /// Disjoint rows of these buffers are written by different threads.
  private struct Targets<S: RayScalar>: @unchecked Sendable {
    let depth: UnsafeMutableBufferPointer<S>
    let normals: UnsafeMutableBufferPointer<Vector3<S>>
    let color: UnsafeMutableBufferPointer<RGB<S>>
  }

  /// Columns per tile: with a batch's rows, the tiles whose spheres are
  /// culled together (scenes without a hierarchy).
  static let tileWidth = 16

  /// Renders a batch of rows, tile by tile when the scene culls spheres per
  /// tile: each tile tests only the spheres its rays may hit.
  private static func renderRows<Kernel: IntersectionKernel, R: RayScalar>(
    _ rows: Range<Int>, _ columns: UnsafeBufferPointer<R>, _ scene: CompiledScene<Kernel>,
    _ camera: PerspectiveCamera<R>, _ settings: RenderSettings, _ tiles: ScreenTiles<Kernel>?,
    _ targets: Targets<Kernel.Scalar>
  ) {
    if let tiles {
      let width = ScreenTiles<Kernel>.tileWidth
      for start in stride(from: 0, to: settings.width, by: width) {
        renderProjectedTile(
          tiles.entries(ofTileAt: start, row: rows.lowerBound),
          columns: start..<min(start + width, settings.width), rows: rows,
          columns, scene, camera, settings, targets)
      }
      return
    }
    // Supersampled rays leave the pixel centres' frusta: no culling then.
    guard scene.cullsPerTile && settings.samples == 1 else {
      // Tile by tile all the same: neighbouring rays visit the same nodes
      // and spheres, which then stay in cache.
      for start in stride(from: 0, to: settings.width, by: tileWidth) {
        let tile = start..<min(start + tileWidth, settings.width)
        for row in rows {
          renderRow(row, tile, nil, columns, scene, camera, settings, targets)
        }
      }
      return
    }
    let aspect = R(settings.height) / R(settings.width)
    let top: R = settings.style.screenY(row: rows.lowerBound, height: settings.height)
    let bottom: R = settings.style.screenY(row: rows.upperBound - 1, height: settings.height)
    withUnsafeTemporaryAllocation(of: Int32.self, capacity: scene.sphereCount) { candidates in
      for start in stride(from: 0, to: settings.width, by: tileWidth) {
        let tile = start..<min(start + tileWidth, settings.width)
        let (left, right) = (columns[tile.lowerBound], columns[tile.upperBound - 1])
        func corner(_ x: R, _ y: R) -> Vector3<Double> {
          Vector3<Double>(camera.rayDirection(x: x, y: y, aspect: aspect))
        }
        let corners = (
          corner(left, top), corner(right, top), corner(right, bottom), corner(left, bottom)
        )
        let count = scene.cullSpheres(corners: corners, into: candidates)
        let chosen = UnsafeBufferPointer(rebasing: candidates[0..<count])
        for row in rows {
          renderRow(row, tile, chosen, columns, scene, camera, settings, targets)
        }
      }
    }
  }

  private static func renderRow<Kernel: IntersectionKernel, R: RayScalar>(
    _ row: Int, _ tile: Range<Int>, _ candidates: UnsafeBufferPointer<Int32>?,
    _ columns: UnsafeBufferPointer<R>, _ scene: CompiledScene<Kernel>,
    _ camera: PerspectiveCamera<R>, _ settings: RenderSettings,
    _ targets: Targets<Kernel.Scalar>
  ) {
    typealias S = Kernel.Scalar
    let width = settings.width
    let style = settings.style
    let aspect = R(settings.height) / R(width)
    let y: R = style.screenY(row: row, height: settings.height)
    let rowBase = camera.rowBase(y: y, aspect: aspect)
    let wantsColor = targets.color.count > 0
    // The tile's directions first, in a loop without calls, so that the
    // processor overlaps one pixel's square root and division with the
    // next one's instead of waiting on each behind a traversal. At most
    // 16 vectors: 768 bytes in Float80, on the stack.
    precondition(tile.count <= tileWidth)
    withUnsafeTemporaryAllocation(of: Vector3<S>.self, capacity: tileWidth) { directions in
      for column in tile {
        (directions.baseAddress! + (column - tile.lowerBound)).initialize(
          to: Vector3<S>(camera.rayDirection(x: columns[column], rowBase: rowBase)))
      }
      for column in tile {
        let direction = directions[column - tile.lowerBound]
        let ray = CameraRay(origin: scene.rayOrigin, direction: direction)
        let pixel = row * width + column
        if wantsColor && settings.samples > 1 {
          targets.color[pixel] = supersampledColor(
            column: column, row: row, scene: scene, camera: camera, settings: settings)
        }
        let hit = scene.nearest(ray, candidates: candidates)
        store(hit, ray: ray, pixel: pixel, scene: scene, settings: settings, targets: targets)
      }
    }
  }

  /// Renders one tile of `ScreenTiles`: each sphere tested only against the
  /// rays of its box's pixels, in scene order with the flat loop's strict
  /// `<`, then each pixel's search continued past the spheres.
  private static func renderProjectedTile<Kernel: IntersectionKernel, R: RayScalar>(
    _ entries: ArraySlice<ScreenTiles<Kernel>.Entry>, columns tileColumns: Range<Int>, rows: Range<Int>,
    _ columns: UnsafeBufferPointer<R>, _ scene: CompiledScene<Kernel>,
    _ camera: PerspectiveCamera<R>, _ settings: RenderSettings,
    _ targets: Targets<Kernel.Scalar>
  ) {
    typealias S = Kernel.Scalar
    let aspect = R(settings.height) / R(settings.width)
    let capacity = ScreenTiles<Kernel>.tileWidth * ScreenTiles<Kernel>.tileHeight
    precondition(tileColumns.count <= ScreenTiles<Kernel>.tileWidth && rows.count <= ScreenTiles<Kernel>.tileHeight)
    withUnsafeTemporaryAllocation(of: CameraRay<S>.self, capacity: capacity) { rays in
      withUnsafeTemporaryAllocation(of: S.self, capacity: capacity) { nearestT in
        withUnsafeTemporaryAllocation(of: Int32.self, capacity: capacity) { nearestEntry in
          for row in rows {
            let y: R = settings.style.screenY(row: row, height: settings.height)
            let rowBase = camera.rowBase(y: y, aspect: aspect)
            for column in tileColumns {
              let slot = (row - rows.lowerBound) * ScreenTiles<Kernel>.tileWidth + column - tileColumns.lowerBound
              (rays.baseAddress! + slot).initialize(
                to: CameraRay(
                  origin: scene.rayOrigin,
                  direction: Vector3<S>(camera.rayDirection(x: columns[column], rowBase: rowBase))))
              (nearestT.baseAddress! + slot).initialize(to: .infinity)
              (nearestEntry.baseAddress! + slot).initialize(to: -1)
            }
          }
          // The nearest entry rather than sphere: its copy of the record is
          // in cache for the normal, the scene's is not.
          let entryBase = entries.startIndex
          for position in entries.indices {
            let entry = entries[position]
            let record = entry.record
            for row in Int(entry.firstRow)...Int(entry.lastRow) {
              for column in Int(entry.firstColumn)...Int(entry.lastColumn) {
                let slot = row * ScreenTiles<Kernel>.tileWidth + column
                if let t = Kernel.intersect(record, rays[slot], before: nearestT[slot]) {
                  nearestT[slot] = t
                  nearestEntry[slot] = Int32(truncatingIfNeeded: position - entryBase)
                }
              }
            }
          }
          for row in rows {
            for column in tileColumns {
              let slot = (row - rows.lowerBound) * ScreenTiles<Kernel>.tileWidth + column - tileColumns.lowerBound
              let position = Int(nearestEntry[slot])
              let entry = position >= 0 ? entries[entryBase + position] : nil
              let hit = scene.nearest(
                rays[slot], beyondSpheres: nearestT[slot], entry.map { .sphere(Int($0.sphere)) })
              store(
                hit, ray: rays[slot], pixel: row * settings.width + column, scene: scene,
                settings: settings, targets: targets, sphereRecord: entry?.record)
            }
          }
        }
      }
    }
  }

  /// Writes a pixel's requested outputs from its nearest hit (nil: none).
  /// `sphereRecord`, when given, is a copy of the record of the sphere the
  /// search found, for the normal if that sphere is still the nearest.
  @inline(__always)
  private static func store<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest)?,
    ray: CameraRay<Kernel.Scalar>, pixel: Int, scene: CompiledScene<Kernel>,
    settings: RenderSettings, targets: Targets<Kernel.Scalar>,
    sphereRecord: Kernel.SphereRecord? = nil
  ) {
    let wantsDepth = targets.depth.count > 0
    let wantsNormals = targets.normals.count > 0
    let shadeCentre = targets.color.count > 0 && settings.samples == 1
    guard let hit else {
      if wantsDepth { targets.depth[pixel] = .infinity }
      if wantsNormals { targets.normals[pixel] = .zero }
      if shadeCentre { targets.color[pixel] = scene.background }
      return
    }
    if wantsDepth { targets.depth[pixel] = hit.t }
    guard wantsNormals || shadeCentre else { return }
    let normal: Vector3<Kernel.Scalar>
    if case .sphere = hit.what, let sphereRecord {
      normal = Kernel.normal(sphereRecord, ray, t: hit.t)
    } else {
      normal = scene.normal(of: hit.what, ray, t: hit.t)
    }
    if wantsNormals { targets.normals[pixel] = normal }
    if shadeCentre {
      targets.color[pixel] = shade(
        hit, ray: ray, normal: normal, scene: scene, attenuate: settings.style == .mit)
    }
  }

  @inline(__always)
  private static func shade<Kernel: IntersectionKernel>(
    _ hit: (t: Kernel.Scalar, what: CompiledScene<Kernel>.Nearest),
    ray: CameraRay<Kernel.Scalar>, normal: Vector3<Kernel.Scalar>,
    scene: CompiledScene<Kernel>, attenuate: Bool
  ) -> RGB<Kernel.Scalar> {
    scene.shadingMaterial(of: hit.what, ray).shade(
      point: scene.eye + ray.direction * hit.t, normal: normal,
      viewDirection: ray.direction, ambient: scene.ambient,
      lights: scene.lights, attenuate: attenuate)
  }

  /// The pixel's colour: the mean of its samples' (`PixelSamples`).
  private static func supersampledColor<Kernel: IntersectionKernel, R: RayScalar>(
    column: Int, row: Int, scene: CompiledScene<Kernel>, camera: PerspectiveCamera<R>,
    settings: RenderSettings
  ) -> RGB<Kernel.Scalar> {
    typealias S = Kernel.Scalar
    var sum = RGB<S>.zero
    var samples = PixelSamples(
      column: column, row: row, camera: camera, settings: settings)
    while let sample = samples.next() {
      let ray = CameraRay(origin: scene.rayOrigin, direction: Vector3<S>(sample))
      guard let hit = scene.nearest(ray) else {
        sum += scene.background
        continue
      }
      let normal = scene.normal(of: hit.what, ray, t: hit.t)
      sum += shade(
        hit, ray: ray, normal: normal, scene: scene,
        attenuate: settings.style == .mit)
    }
    return sum / S(samples.count)
  }

  /// Rows per batch: small enough to balance two threads on a 100-row image,
  /// large enough that taking a batch costs nothing next to rendering it.
  static let rowsPerBatch = 4

  /// Runs `body` over all rows in batches on `threads` workers (the calling
  /// thread among them), reporting finished rows to `progress`.
  static func forEachRowBatch(
    rows: Int, threads: Int, progress: (@Sendable (Int) -> Void)?,
    _ body: @Sendable (Range<Int>) -> Void
  ) {
    let batches = (rows + rowsPerBatch - 1) / rowsPerBatch
    let next = AtomicCounter(0)
    let done = AtomicCounter(0)
    let workers = max(1, min(threads, batches))
    withoutActuallyEscaping(body) { body in
      let work: @Sendable () -> Void = {
        while true {
          let batch = next.add(1).old
          guard batch < batches else { return }
          let start = batch * rowsPerBatch
          let end = min(rows, start + rowsPerBatch)
          body(start..<end)
          let finished = done.add(end - start).new
          progress?(finished)
        }
      }
      if workers == 1 {
        work()
      } else {
        DispatchQueue.concurrentPerform(iterations: workers) { _ in work() }
      }
    }
  }
}

extension Renderer {
  /// The number of processors online, the default thread count.
  public static var availableCores: Int {
    max(1, Int(sysconf(Int32(_SC_NPROCESSORS_ONLN))))
  }
}
