import Geometry
import SceneDescription
import PlatformSupport

/// Spheres sorted by the screen tiles their silhouettes may cover: the
/// primary-ray search turned around, object by object, as molecular viewers
/// draw millions of atoms. In a supersampled render each box is widened by
/// the pixel filter's reach, and every sample is searched the same way.
///
/// A camera ray through screen point (x, y) has direction M·(x, y, 1) with
/// M = [u, (H/W)·v, D·w]; the ball of radius ρ about p is reachable from
/// the eye only along directions whose screen point lies inside an ellipse,
/// and that ellipse's bounding box has a closed form (see `screenInterval`).
/// Each sphere's box, in pixels and widened for every rounding on the way,
/// is recorded in the 256×4-pixel tiles it touches, in scene order, so the
/// render tests each pixel's ray against only the spheres whose boxes hold
/// it, with the flat loop's strict `<`: the nearest hit, ties included, is
/// the one testing every sphere finds.
///
/// Each entry carries a copy of its sphere's record: the tiles list the
/// spheres in an order unrelated to the scene's, and the load of a record
/// through its index, missing the cache, took 56% of the tile loop's time
/// at a million spheres (`perf annotate`); the normal of the sphere a
/// pixel sees is computed from the same copy.
///
/// The work is the sum of the boxes' areas: one box per sphere, a few
/// pixels each for a million small spheres, where a hierarchy's walk per
/// ray grows with the scene's depth. Where spheres overlap heavily on
/// screen (big spheres one behind another) that sum outgrows the image and
/// a hierarchy is cheaper: `init` declines then.
struct ScreenTiles<Kernel: IntersectionKernel>: Sendable {
  /// Tiles a batch of rows high and 256 pixels wide: a tile's rays (64 KiB
  /// in Double) stay in the level-2 cache while its spheres are tested,
  /// and sorting entries into a few thousand tiles writes each tile's
  /// list through a cache line that stays resident. With 16-pixel tiles
  /// (32,400 at 1920×1080) every entry written and every record read
  /// missed the cache.
  static var tileWidth: Int { ScreenTilesGeometry.tileWidth }
  static var tileHeight: Int { Renderer.rowsPerBatch }

  /// A sphere's pixels within one tile: columns and rows relative to the
  /// tile's corner, both ends included.
  struct Entry: Sendable {
    var record: Kernel.SphereRecord
    var sphere: Int32
    var firstColumn: UInt16
    var lastColumn: UInt16
    var firstRow: UInt8
    var lastRow: UInt8
  }

  /// A triangle's pixels within one tile (`TriangleTiles`), as `Entry`:
  /// 8 bytes, its columns within a tile 256 wide held in a byte each (12
  /// bytes had been 23 MiB of a 5·10⁶-triangle render's peak).
  struct TriangleEntry: Sendable {
    var triangle: Int32
    var firstColumn: UInt8
    var lastColumn: UInt8
    var firstRow: UInt8
    var lastRow: UInt8
  }

  let tilesAcross: Int
  /// Tile t's entries are entries[starts[t]..<starts[t + 1]], tiles row by row.
  let starts: [Int]
  let entries: [Entry]
  /// The same for the triangles when the scene projects them, else empty.
  let triangleStarts: [Int]
  let triangleEntries: [TriangleEntry]
  /// The sum of the spheres' and triangles' boxes in pixels: the tests
  /// the render makes.
  let coveredPixels: Int

  /// Where a hierarchy wins: boxes summing to more than this many times
  /// the image's pixels (measured: docs/PERFORMANCE.md, "Thresholds").
  static var overlapLimit: Int { 32 }

  func entries(ofTileAt column: Int, row: Int) -> ArraySlice<Entry> {
    let tile = (row / Self.tileHeight) * tilesAcross + column / Self.tileWidth
    return entries[starts[tile]..<starts[tile + 1]]
  }

  /// The triangles' entries of the tile; empty unless the scene projects
  /// its triangles.
  func triangleEntries(ofTileAt column: Int, row: Int) -> ArraySlice<
    TriangleEntry
  > {
    guard !triangleStarts.isEmpty else { return [] }
    let tile = (row / Self.tileHeight) * tilesAcross + column / Self.tileWidth
    return triangleEntries[triangleStarts[tile]..<triangleStarts[tile + 1]]
  }

  /// Nil when the boxes sum to more than `overlapLimit` times the image,
  /// or the entries to more than twice the pixels and primitives together.
  ///
  /// - Parameter camera: the camera the render builds its rays with
  ///   (`styled`), in the precision of the render's rays.
  init?(
    _ scene: CompiledScene<Kernel>, camera: PerspectiveCamera<Kernel.Scalar>,
    settings: RenderSettings, overlapLimit: Int = Self.overlapLimit
  ) {
    let (width, height) = (settings.width, settings.height)
    tilesAcross = (width + Self.tileWidth - 1) / Self.tileWidth
    let projection = ScreenProjection(
      camera: PerspectiveCamera<Double>(camera), screen: settings.screen)
    // A supersampled pixel's rays reach out to the filter's reach from its
    // centre (`PixelSamples`); 1/16 pixel more covers the rounding of
    // their screen coordinates (a few ε of a value within 2).
    let margin = settings.sampleMargin
    let limit = Double(overlapLimit) * Double(width * height)
    var spheres = TileLists<Entry>(
      tilesAcross: tilesAcross, width: width, height: height)
    let sphereArea = scene.spheres.withUnsafeBufferPointer { records in
      spheres.sort(
        count: records.count, threads: settings.threads, areaLimit: limit,
        box: { index in
          let (center, reach) = scene.cullBound(records[index])
          return projection.pixelBox(
            center: center, reach: reach, margin: margin)
        },
        entry: { index, columns, rows in
          Entry(
            record: records[index], sphere: Int32(truncatingIfNeeded: index),
            firstColumn: columns.0, lastColumn: columns.1, firstRow: rows.0,
            lastRow: rows.1)
        })
    }
    guard let sphereArea else { return nil }
    var triangleArea = 0
    if scene.projectsTriangles {
      var triangles = TileLists<TriangleEntry>(
        tilesAcross: tilesAcross, width: width, height: height)
      let area = scene.triangles.withUnsafeBufferPointer { records in
        triangles.sort(
          count: scene.triangles.count, threads: settings.threads,
          areaLimit: limit - Double(sphereArea),
          box: { index in
            scene.triangleBox(records[index], projection, margin: margin)
          },
          entry: { index, columns, rows in
            TriangleEntry(
              triangle: Int32(truncatingIfNeeded: index),
              firstColumn: UInt8(columns.0), lastColumn: UInt8(columns.1),
              firstRow: rows.0, lastRow: rows.1)
          })
      }
      guard let area else { return nil }
      triangleArea = area
      triangleStarts = triangles.starts
      triangleEntries = triangles.entries
    } else {
      triangleStarts = []
      triangleEntries = []
    }
    coveredPixels = sphereArea + triangleArea
    starts = spheres.starts
    entries = spheres.entries
  }
}

/// Primitives sorted into screen tiles by their pixel boxes, each tile's
/// entries in the primitives' order: the lists of `ScreenTiles`.
struct TileLists<Entry> {
  let tilesAcross: Int
  let tileCount: Int
  let width: Int
  let height: Int
  /// Tile t's entries are entries[starts[t]..<starts[t + 1]].
  private(set) var starts: [Int] = []
  private(set) var entries: [Entry] = []

  init(tilesAcross: Int, width: Int, height: Int) {
    let tileHeight = Renderer.rowsPerBatch
    self.tilesAcross = tilesAcross
    tileCount = tilesAcross * ((height + tileHeight - 1) / tileHeight)
    self.width = width
    self.height = height
  }

  /// Sorts primitives 0..<count into the tiles their `box` touches, each
  /// clipped to the tile by `entry` (columns and rows relative to the
  /// tile's corner, both ends included), and returns the boxes' total area;
  /// nil, with nothing stored, when that area exceeds `areaLimit` or the
  /// entries exceed twice the pixels and primitives together (past that
  /// their memory would outgrow the render's own buffers: a hierarchy
  /// then).
  ///
  /// From 2¹⁴ primitives, with `threads` above 1, the boxes are computed
  /// and the entries written in parts of at least 2¹³ primitives, one per
  /// thread; tile by tile each part's entries come before the next part's,
  /// so every tile lists its primitives in order, whatever the threads.
  /// (Two parts at most, as it was, held a 10⁶-triangle render to 3× on
  /// 16 cores: docs/PERFORMANCE.md, "Scaling with cores".)
  mutating func sort(
    count: Int, threads: Int, areaLimit: Double,
    box: (Int) -> PixelBox,
    entry: (Int, (UInt16, UInt16), (UInt8, UInt8)) -> Entry
  ) -> Int? {
    // 8 bytes a box where the image's sides fit 16 bits: 16 had been
    // 76 MiB of a 5·10⁶-triangle render's peak, here.
    guard width <= 1 << 16 && height <= 1 << 16 else {
      return sort(
        count: count, threads: threads, areaLimit: areaLimit, box: box,
        entry: entry, storing: PixelBox.self)
    }
    return sort(
      count: count, threads: threads, areaLimit: areaLimit, box: box,
      entry: entry, storing: PackedPixelBox.self)
  }

  /// `sort`, each box kept between the passes as a `Stored`.
  private mutating func sort<Stored: StoredPixelBox>(
    count: Int, threads: Int, areaLimit: Double,
    box: (Int) -> PixelBox,
    entry: (Int, (UInt16, UInt16), (UInt8, UInt8)) -> Entry,
    storing _: Stored.Type
  ) -> Int? {
    let (tilesAcross, tileCount) = (self.tilesAcross, self.tileCount)
    let (tileWidth, tileHeight) = (
      ScreenTilesGeometry.tileWidth, Renderer.rowsPerBatch
    )
    let parts =
      count >= 1 << 14 ? Swift.max(1, Swift.min(threads, count >> 13)) : 1
    // Pass one: each primitive's box, and per part how many entries each
    // tile gets from it, so that pass two writes every entry into place.
    var tileCounts = [[Int32]](repeating: [], count: parts)
    var covered = [Int](repeating: 0, count: parts)
    let boxes = [Stored](unsafeUninitializedCapacity: count) {
      boxes, initialized in
      Memory.adviseHugePages(UnsafeMutableRawBufferPointer(boxes))
      withoutActuallyEscaping(box) { box in
        let (sharedBox, shared) = (Shared(box), Shared(boxes))
        let results = Shared(
          UnsafeMutableBufferPointer<([Int32], Int)>.allocate(capacity: parts))
        defer { results.value.deallocate() }
        Parallel.inParts(count, parts) { part, range in
          let (box, boxes) = (sharedBox.value, shared.value)
          var counts = [Int32](repeating: 0, count: tileCount)
          var area = 0
          for index in range {
            let box = box(index)
            (boxes.baseAddress! + index).initialize(to: Stored(box))
            guard !box.isEmpty else { continue }
            area += box.area
            for tileRow in box.rows.lowerBound / tileHeight...box.rows
              .upperBound / tileHeight
            {
              let base = tileRow * tilesAcross
              for tileColumn in box.columns.lowerBound / tileWidth...box.columns
                .upperBound / tileWidth
              {
                counts[base + tileColumn] += 1
              }
            }
          }
          (results.value.baseAddress! + part).initialize(to: (counts, area))
        }
        for part in 0..<parts {
          (tileCounts[part], covered[part]) = results.value[part]
        }
        results.value.baseAddress!.deinitialize(count: parts)
      }
      initialized = count
    }
    let area = covered.reduce(0, +)
    guard Double(area) <= areaLimit else { return nil }
    // Tile by tile, part 0's entries before part 1's: the primitives' order.
    var starts = [Int](repeating: 0, count: tileCount + 1)
    var cursors = [[Int]](
      repeating: [Int](repeating: 0, count: tileCount), count: parts)
    var total = 0
    for tile in 0..<tileCount {
      starts[tile] = total
      for part in 0..<parts {
        cursors[part][tile] = total
        total += Int(tileCounts[part][tile])
      }
    }
    starts[tileCount] = total
    // Entries are mostly one or two per primitive and one per 1,024 pixels
    // of a big box; thin boxes spanning many tiles could make them far
    // more.
    guard total <= 2 * (width * height + count) else { return nil }
    self.starts = starts
    entries = Array(unsafeUninitializedCapacity: total) {
      entries, initialized in
      Memory.adviseHugePages(UnsafeMutableRawBufferPointer(entries))
      withoutActuallyEscaping(entry) { entry in
        let (shared, sharedEntry) = (Shared((entries, cursors)), Shared(entry))
        boxes.withUnsafeBufferPointer { boxes in
          let boxes = Shared(boxes)
          Parallel.inParts(count, parts) { part, range in
            let (entries, cursors) = shared.value
            let entry = sharedEntry.value
            var cursor = cursors[part]
            for index in range {
              let box = boxes.value[index].box
              guard !box.isEmpty else { continue }
              let (columns, rows) = (box.columns, box.rows)
              for tileRow in rows.lowerBound / tileHeight...rows.upperBound
                / tileHeight
              {
                let top = tileRow * tileHeight
                let rowsInTile = (
                  UInt8(Swift.max(rows.lowerBound, top) - top),
                  UInt8(Swift.min(rows.upperBound, top + tileHeight - 1) - top)
                )
                for tileColumn in columns.lowerBound / tileWidth...columns
                  .upperBound / tileWidth
                {
                  let left = tileColumn * tileWidth
                  let tile = tileRow * tilesAcross + tileColumn
                  (entries.baseAddress! + cursor[tile]).initialize(
                    to: entry(
                      index,
                      (
                        UInt16(Swift.max(columns.lowerBound, left) - left),
                        UInt16(
                          Swift.min(columns.upperBound, left + tileWidth - 1)
                            - left)
                      ), rowsInTile))
                  cursor[tile] += 1
                }
              }
            }
          }
        }
      }
      initialized = total
    }
    return area
  }
}

/// A pixel box as `TileLists.sort` keeps it between its passes.
protocol StoredPixelBox {
  init(_ box: PixelBox)
  var box: PixelBox { get }
}

extension PixelBox: StoredPixelBox {
  init(_ box: PixelBox) { self = box }
  var box: PixelBox { self }
}

/// A box inside an image whose sides fit 16 bits, or empty: 8 bytes.
struct PackedPixelBox: StoredPixelBox {
  var firstColumn, lastColumn, firstRow, lastRow: UInt16

  init(_ box: PixelBox) {
    guard !box.isEmpty else {
      (firstColumn, lastColumn, firstRow, lastRow) = (1, 0, 1, 0)
      return
    }
    firstColumn = UInt16(truncatingIfNeeded: box.firstColumn)
    lastColumn = UInt16(truncatingIfNeeded: box.lastColumn)
    firstRow = UInt16(truncatingIfNeeded: box.firstRow)
    lastRow = UInt16(truncatingIfNeeded: box.lastRow)
  }

  var box: PixelBox {
    PixelBox(
      firstColumn: Int32(firstColumn), lastColumn: Int32(lastColumn),
      firstRow: Int32(firstRow), lastRow: Int32(lastRow))
  }
}

/// The tiles' width, shared by every kernel's `ScreenTiles`.
enum ScreenTilesGeometry {
  static var tileWidth: Int { 256 }
}
