import Geometry
import SceneDescription
import PlatformSupport

/// The pixel loop: rows in tiles, each tile's rays generated together,
/// then each pixel's nearest hit by the scene's sphere search.
extension Renderer {
  /// Columns per tile: with a batch's rows, the tiles whose spheres are
  /// culled together (scenes without a hierarchy).
  static let tileWidth = 16

  /// Renders a batch of rows, tile by tile when the scene culls spheres per
  /// tile: each tile tests only the spheres its rays may hit.
  static func renderRows<Kernel: IntersectionKernel, R: RayScalar>(
    _ rows: Range<Int>, _ columns: UnsafeBufferPointer<R>,
    _ scene: CompiledScene<Kernel>,
    _ camera: PerspectiveCamera<R>, _ settings: RenderSettings,
    _ tiles: ScreenTiles<Kernel>?,
    _ targets: Targets<Kernel.Scalar>
  ) {
    if let tiles {
      let width = ScreenTiles<Kernel>.tileWidth
      for start in stride(from: 0, to: settings.width, by: width) {
        let entries = tiles.entries(ofTileAt: start, row: rows.lowerBound)
        let triangleEntries = tiles.triangleEntries(
          ofTileAt: start, row: rows.lowerBound)
        let tile = start..<min(start + width, settings.width)
        // The pixel centres for what is not supersampled, then the samples.
        let all = settings.supersamplesAll
        if !all
          && (!settings.supersamples || targets.wantsDepth
            || targets.wantsNormals)
        {
          renderProjectedTile(
            entries, triangleEntries, columns: tile, rows: rows, columns,
            scene, camera, settings, targets)
        }
        if all || (settings.supersamples && targets.wantsColor) {
          renderProjectedSamples(
            entries, triangleEntries, columns: tile, rows: rows, scene, camera,
            settings, targets)
        }
      }
      return
    }
    guard scene.cullsPerTile else {
      if scene.usesHierarchy {
        renderTiles(
          rows, by: SphereHierarchy(), columns, scene, camera, settings,
          targets)
      } else {
        renderTiles(
          rows, by: EverySphere(), columns, scene, camera, settings, targets)
      }
      return
    }
    let aspect = R(settings.height) / R(settings.width)
    // Supersampled rays leave the pixel centres' pyramid, by at most the
    // filter's reach (`PixelFilter.reach`) in pixels; the pyramid is
    // widened by that and by 1/16 pixel more, which covers the rounding of
    // a sample's screen coordinates (a few ε of a value within 2).
    let reach = settings.sampleMargin
    let screen = settings.screen
    let (stepX, stepY) = (
      R(reach) * (columns.count > 1 ? columns[1] - columns[0] : 2),
      R(reach)
        * (settings.height > 1
          ? screen.y(row: 0) - screen.y(row: 1) as R : 2)
    )
    let top: R = screen.y(row: rows.lowerBound) + stepY
    let bottom: R = screen.y(row: rows.upperBound - 1) - stepY
    withUnsafeTemporaryAllocation(of: Int32.self, capacity: scene.sphereCount) {
      candidates in
      for start in stride(from: 0, to: settings.width, by: tileWidth) {
        let tile = start..<min(start + tileWidth, settings.width)
        let (left, right) = (
          columns[tile.lowerBound] - stepX, columns[tile.upperBound - 1] + stepX
        )
        func corner(_ x: R, _ y: R) -> Vector3<Double> {
          Vector3<Double>(camera.rayDirection(x: x, y: y, aspect: aspect))
        }
        let corners = (
          corner(left, top), corner(right, top), corner(right, bottom),
          corner(left, bottom)
        )
        let count = scene.cullSpheres(corners: corners, into: candidates)
        let chosen = CulledSpheres(
          candidates: UnsafeBufferPointer(rebasing: candidates[0..<count]))
        for row in rows {
          renderRow(
            row, tile, chosen, columns, scene, camera, settings, targets)
        }
      }
    }
  }

  /// Renders a batch of rows tile by tile, every tile's spheres found by
  /// `search`: neighbouring rays visit the same nodes and spheres, which
  /// then stay in cache.
  static func renderTiles<
    Kernel: IntersectionKernel, R: RayScalar, Search: NearestSphereSearch
  >(
    _ rows: Range<Int>, by search: Search,
    _ columns: UnsafeBufferPointer<R>, _ scene: CompiledScene<Kernel>,
    _ camera: PerspectiveCamera<R>, _ settings: RenderSettings,
    _ targets: Targets<Kernel.Scalar>
  ) {
    for start in stride(from: 0, to: settings.width, by: tileWidth) {
      let tile = start..<min(start + tileWidth, settings.width)
      for row in rows {
        renderRow(row, tile, search, columns, scene, camera, settings, targets)
      }
    }
  }

  static func renderRow<
    Kernel: IntersectionKernel, R: RayScalar, Search: NearestSphereSearch
  >(
    _ row: Int, _ tile: Range<Int>, _ search: Search,
    _ columns: UnsafeBufferPointer<R>, _ scene: CompiledScene<Kernel>,
    _ camera: PerspectiveCamera<R>, _ settings: RenderSettings,
    _ targets: Targets<Kernel.Scalar>
  ) {
    typealias S = Kernel.Scalar
    let width = settings.width
    let aspect = R(settings.height) / R(width)
    let y: R = settings.screen.y(row: row)
    let rowBase = camera.rowBase(y: y, aspect: aspect)
    let wantsColor = targets.wantsColor
    if settings.supersamplesAll {
      for column in tile {
        supersample(
          column: column, row: row, by: search, scene: scene, camera: camera,
          settings: settings, targets: targets)
      }
      return
    }
    // The tile's directions first, in a loop without calls, so that the
    // processor overlaps one pixel's square root and division with the
    // next one's instead of waiting on each behind a traversal. At most
    // 16 vectors: 768 bytes in Float80, on the stack.
    precondition(tile.count <= tileWidth)
    withUnsafeTemporaryAllocation(of: Vector3<S>.self, capacity: tileWidth) {
      directions in
      for column in tile {
        (directions.baseAddress! + (column - tile.lowerBound)).initialize(
          to: Vector3<S>(
            camera.rayDirection(x: columns[column], rowBase: rowBase)))
      }
      for column in tile {
        let direction = directions[column - tile.lowerBound]
        let ray = CameraRay(origin: scene.rayOrigin, direction: direction)
        let pixel = row * width + column
        if wantsColor && settings.supersamples {
          supersample(
            column: column, row: row, by: search, scene: scene,
            camera: camera, settings: settings, targets: targets)
        }
        // No spheres: no sphere search and no sphere memo to carry through
        // the pixel (carried, it cost a triangle scene a sixth of its
        // time in float).
        guard !scene.spheres.isEmpty else {
          store(
            scene.nearest(ray, after: NearestHit(before: .infinity)),
            ray: ray, pixel: pixel, scene: scene, settings: settings,
            targets: targets)
          continue
        }
        var memo = Kernel.noMemo
        let hit = scene.nearest(
          ray, after: search.nearestSphere(ray, in: scene, memo: &memo))
        store(
          hit, ray: ray, pixel: pixel, scene: scene, settings: settings,
          targets: targets, sphereMemo: memo)
      }
    }
  }
}
