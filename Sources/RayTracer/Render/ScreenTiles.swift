/// Spheres sorted by the screen tiles their silhouettes may cover: the
/// primary-ray search of a single-sample render turned around, object by
/// object, as molecular viewers draw millions of atoms.
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
  static var tileWidth: Int { 256 }
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

  let tilesAcross: Int
  /// Tile t's entries are entries[starts[t]..<starts[t + 1]], tiles row by row.
  let starts: [Int]
  let entries: [Entry]
  /// The sum of the spheres' boxes in pixels: the sphere tests the render makes.
  let coveredPixels: Int

  /// Where a hierarchy wins: boxes summing to more than this many times
  /// the image's pixels. Measured at 1920×1080, depth and normals, one
  /// thread, render time only (the hierarchy's build not counted), random
  /// spheres as `gen_spheres.py` lays them out with larger radii: at
  /// overlaps of 4.4 / 9.9 / 16 / 34 / 38 / 41 / 56 the tiles took 156 /
  /// 241 / 273 / 318 / 329 / 429 / 381 ms and the hierarchy 259 / 294 /
  /// 276 / 315 / 324 / 369 / 377 ms (2,000 to 100,000 spheres). The
  /// default (1.2) is far below.
  static var overlapLimit: Int { 32 }

  func entries(ofTileAt column: Int, row: Int) -> ArraySlice<Entry> {
    let tile = (row / Self.tileHeight) * tilesAcross + column / Self.tileWidth
    return entries[starts[tile]..<starts[tile + 1]]
  }

  /// Nil when the boxes sum to more than `overlapLimit` times the image,
  /// or the entries to more than twice the pixels and spheres together.
  ///
  /// - Parameter camera: the camera the render builds its rays with
  ///   (`styled`), in the precision of the render's rays.
  init?(
    _ scene: CompiledScene<Kernel>, camera: PerspectiveCamera<Kernel.Scalar>,
    settings: RenderSettings, overlapLimit: Int = Self.overlapLimit
  ) {
    let (width, height) = (settings.width, settings.height)
    tilesAcross = (width + Self.tileWidth - 1) / Self.tileWidth
    let tilesDown = (height + Self.tileHeight - 1) / Self.tileHeight
    let tileCount = tilesAcross * tilesDown
    let projection = ScreenProjection(
      camera: PerspectiveCamera<Double>(camera), width: width, height: height,
      style: settings.style)
    let count = scene.spheres.count
    let parts = count >= 1 << 14 ? Swift.max(1, Swift.min(settings.threads, 2)) : 1
    // Pass one: each sphere's box, and per part how many entries each tile
    // gets from it, so that pass two writes every entry straight into place.
    var tileCounts = [[Int32]](repeating: [], count: parts)
    var covered = [Int](repeating: 0, count: parts)
    let (tilesAcross, tileWidth, tileHeight) = (tilesAcross, Self.tileWidth, Self.tileHeight)
    let boxes = [PixelBox](unsafeUninitializedCapacity: count) { boxes, initialized in
      Memory.adviseHugePages(UnsafeMutableRawBufferPointer(boxes))
      scene.spheres.withUnsafeBufferPointer { records in
        let shared = Shared((records, boxes))
        let results = Shared(
          UnsafeMutableBufferPointer<([Int32], Int)>.allocate(capacity: parts))
        defer { results.value.deallocate() }
        Parallel.inParts(count, parts) { part, range in
          let (records, boxes) = shared.value
          var counts = [Int32](repeating: 0, count: tileCount)
          var area = 0
          for index in range {
            let (center, reach) = scene.cullBound(records[index])
            let box = projection.pixelBox(center: center, reach: reach)
            (boxes.baseAddress! + index).initialize(to: box)
            guard !box.isEmpty else { continue }
            area += box.area
            for tileRow in box.rows.lowerBound / tileHeight...box.rows.upperBound / tileHeight {
              let base = tileRow * tilesAcross
              for tileColumn in box.columns.lowerBound / tileWidth...box.columns.upperBound / tileWidth {
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
    coveredPixels = covered.reduce(0, +)
    guard Double(coveredPixels) <= Double(overlapLimit) * Double(width * height) else { return nil }
    // Tile by tile, part 0's entries before part 1's: scene order.
    var starts = [Int](repeating: 0, count: tileCount + 1)
    var cursors = [[Int]](repeating: [Int](repeating: 0, count: tileCount), count: parts)
    var total = 0
    for tile in 0..<tileCount {
      starts[tile] = total
      for part in 0..<parts {
        cursors[part][tile] = total
        total += Int(tileCounts[part][tile])
      }
    }
    starts[tileCount] = total
    // Entries are mostly one or two per sphere and one per 1,024 pixels
    // of a big box; thin boxes spanning many tiles could make them far
    // more, each a copy of a record. Past two per pixel and sphere the
    // memory would outgrow the render's own buffers: the hierarchy then.
    guard total <= 2 * (width * height + count) else { return nil }
    self.starts = starts
    entries = Array(unsafeUninitializedCapacity: total) { entries, initialized in
      Memory.adviseHugePages(UnsafeMutableRawBufferPointer(entries))
      let shared = Shared((entries, cursors))
      boxes.withUnsafeBufferPointer { boxes in
        scene.spheres.withUnsafeBufferPointer { records in
        let boxesAndRecords = Shared((boxes, records))
        Parallel.inParts(count, parts) { part, range in
          let (entries, cursors) = shared.value
          let (boxes, records) = boxesAndRecords.value
          var cursor = cursors[part]
          for index in range {
            let box = boxes[index]
            guard !box.isEmpty else { continue }
            let (columns, rows) = (box.columns, box.rows)
            for tileRow in rows.lowerBound / tileHeight...rows.upperBound / tileHeight {
              let top = tileRow * tileHeight
              let rowsInTile = (
                UInt8(Swift.max(rows.lowerBound, top) - top),
                UInt8(Swift.min(rows.upperBound, top + tileHeight - 1) - top)
              )
              for tileColumn in columns.lowerBound / tileWidth...columns.upperBound / tileWidth {
                let left = tileColumn * tileWidth
                let tile = tileRow * tilesAcross + tileColumn
                (entries.baseAddress! + cursor[tile]).initialize(
                  to: Entry(
                    record: records[index], sphere: Int32(truncatingIfNeeded: index),
                    firstColumn: UInt16(Swift.max(columns.lowerBound, left) - left),
                    lastColumn: UInt16(Swift.min(columns.upperBound, left + tileWidth - 1) - left),
                    firstRow: rowsInTile.0, lastRow: rowsInTile.1))
                cursor[tile] += 1
              }
            }
          }
        }
        }
      }
      initialized = total
    }
  }
}

/// Pixels from `firstColumn` to `lastColumn` and `firstRow` to `lastRow`,
/// ends included; empty when first > last.
struct PixelBox: Sendable, Equatable {
  var firstColumn: Int32
  var lastColumn: Int32
  var firstRow: Int32
  var lastRow: Int32

  static let empty = PixelBox(firstColumn: 0, lastColumn: -1, firstRow: 0, lastRow: -1)

  var isEmpty: Bool { firstColumn > lastColumn || firstRow > lastRow }
  /// Only for boxes that are not empty.
  var columns: ClosedRange<Int> { Int(firstColumn)...Int(lastColumn) }
  var rows: ClosedRange<Int> { Int(firstRow)...Int(lastRow) }
  var area: Int { Int(lastColumn - firstColumn + 1) * Int(lastRow - firstRow + 1) }
}

/// The pixels whose camera rays may come within a distance of a point.
struct ScreenProjection: Sendable {
  /// The last row of M⁻¹, M = [u, (H/W)·v, D·w]: rᵢ·d over r₃·d is d's
  /// screen x (i = 1) or y (i = 2), rows 1 and 2 being `axes`.
  let r3: Vector3<Double>
  /// Per camera rather than per sphere: |r₃|, |r₃|², and for each screen
  /// axis rᵢ, |rᵢ|, rᵢ·r₃ and |rᵢ × r₃|².
  let r3Length: Double
  let r3LengthSquared: Double
  let axes: (x: Axis, y: Axis)
  /// A bound on how much the computed rows and products can err, relative
  /// to their sizes: max|column of M|·max|rᵢ| ε-units become this slack.
  let condition: Double
  let width: Int
  let height: Int
  let style: ImageStyle
  let whole: PixelBox

  struct Axis: Sendable {
    let row: Vector3<Double>
    let length: Double
    let dotR3: Double
    let crossR3Squared: Double
  }

  init(camera: PerspectiveCamera<Double>, width: Int, height: Int, style: ImageStyle) {
    let aspect = Double(height) / Double(width)
    let (u, v, w) = (camera.horizontal, camera.up * aspect, camera.direction * camera.focalDistance)
    let determinant = u.dot(v.cross(w))
    let r1 = v.cross(w) / determinant
    let r2 = w.cross(u) / determinant
    r3 = u.cross(v) / determinant
    condition =
      Swift.max(u.length, v.length, w.length) * Swift.max(r1.length, r2.length, r3.length)
    r3Length = r3.length
    r3LengthSquared = r3.lengthSquared
    let r3 = r3
    func axis(_ row: Vector3<Double>) -> Axis {
      Axis(
        row: row, length: row.length, dotR3: row.dot(r3),
        crossR3Squared: row.cross(r3).lengthSquared)
    }
    axes = (axis(r1), axis(r2))
    self.width = width
    self.height = height
    self.style = style
    whole = PixelBox(
      firstColumn: 0, lastColumn: Int32(width - 1), firstRow: 0, lastRow: Int32(height - 1))
  }

  /// The pixels whose rays may pass within `reach` of `center` (relative
  /// to the eye) in front of the eye: every pixel when the ball comes
  /// near the plane through the eye parallel to the screen, where its
  /// silhouette has no bounded box, or when anything is not finite.
  func pixelBox(center p: Vector3<Double>, reach ρ: Double) -> PixelBox {
    let p3 = r3.dot(p)
    let n3 = r3Length
    // A hit point h = t·d has r₃·h > 0 and |h − p| ≤ ρ, so r₃·p > −ρ|r₃|.
    if p3 <= -ρ * n3 * (1 + 0x1p-20) { return .empty }
    // With r₃·p ≥ 2ρ|r₃| the ball is at most 30° wide seen from that
    // plane, A below stays within [3/4, 1]·(r₃·p)², and every quantity is
    // a sum of terms of known size (`Λ`).
    guard p3 >= 2 * ρ * n3, p3.isFinite, ρ.isFinite, p.isFinite else { return whole }
    // Shared by both axes: A, 1/A, 1/P₃ and |p| + ρ (one division each
    // rather than one per axis; the extra rounding is far inside the pad).
    let shared = IntervalTerms(
      p3: p3, ρ: ρ, a: p3 * p3 - ρ * ρ * r3LengthSquared, extent: p.length + ρ)
    guard let x = screenInterval(axes.x, p, shared),
      let y = screenInterval(axes.y, p, shared)
    else { return whole }
    // The pixels whose own screen coordinates lie in the intervals. Those
    // were rounded in the render's precision (`screenX`: a division and a
    // subtraction, within 2 ε of the exact value on [−1, 1]); 4 ε of the
    // widest precision a render takes (Float), times the pixels per
    // screen unit, covers that with room for this Double arithmetic.
    let columns = (
      style.column(screenX: x.lower, width: width), style.column(screenX: x.upper, width: width)
    )
    let rows = (
      style.row(screenY: y.upper, height: height), style.row(screenY: y.lower, height: height)
    )
    let padColumns = 4 * Double(Float.ulpOfOne) * Double(width) + 0x1p-30
    let padRows = 4 * Double(Float.ulpOfOne) * Double(height) + 0x1p-30
    func clamped(_ value: Double, _ limit: Int) -> Int32 {
      Int32(Swift.min(Swift.max(value, -1), Double(limit)))
    }
    let box = PixelBox(
      firstColumn: Swift.max(0, clamped((columns.0 - padColumns).rounded(.up), width)),
      lastColumn: Swift.min(Int32(width - 1), clamped((columns.1 + padColumns).rounded(.down), width)),
      firstRow: Swift.max(0, clamped((rows.0 - padRows).rounded(.up), height)),
      lastRow: Swift.min(Int32(height - 1), clamped((rows.1 + padRows).rounded(.down), height)))
    return box.isEmpty ? .empty : box
  }

  /// The screen coordinates k = rᵢ·d / r₃·d of the directions d within the
  /// ball: the planes (rᵢ − k r₃)·d = 0 tangent to it, where
  /// (rᵢ·p − k r₃·p)² = ρ²|rᵢ − k r₃|², a quadratic A k² − 2B k + C = 0 with
  /// A = P₃² − ρ²|r₃|², B = PᵢP₃ − ρ² rᵢ·r₃ and, by Lagrange's identity,
  /// B² − AC = ρ²(|P₃rᵢ − Pᵢr₃|² − ρ²|rᵢ × r₃|²): the P²ᵢP²₃ that cancel in
  /// the textbook discriminant never appear, so a sphere a billionth of
  /// its distance wide keeps its digits.
  ///
  /// Rounding: each quantity below is a sum of a few products of terms no
  /// larger than Λ·A (Λ defined below, in units of the screen), carrying
  /// at most a few dozen ε of Double each, and A ≥ 3/4·P₃² bounds the
  /// division. The interval is widened by 2⁻³⁰·Λ·condition, about 2²²
  /// times that bound; on screen that is a few billionths of the image.
  struct IntervalTerms {
    let p3: Double
    let ρ: Double
    let a: Double
    let inverseA: Double
    let inverseP3: Double
    let extent: Double

    init(p3: Double, ρ: Double, a: Double, extent: Double) {
      (self.p3, self.ρ, self.a, self.extent) = (p3, ρ, a, extent)
      inverseA = 1 / a
      inverseP3 = 1 / p3
    }
  }

  @inline(__always)
  private func screenInterval(
    _ axis: Axis, _ p: Vector3<Double>, _ terms: IntervalTerms
  ) -> (lower: Double, upper: Double)? {
    let (p3, ρ) = (terms.p3, terms.ρ)
    let ri = axis.row
    let pi = ri.dot(p)
    let b = pi * p3 - ρ * ρ * axis.dotR3
    let tangent = ri * p3 - r3 * pi
    let discriminant = Swift.max(0, tangent.lengthSquared - ρ * ρ * axis.crossR3Squared)
    let s = ρ * discriminant.squareRoot()
    let lower = (b - s) * terms.inverseA
    let upper = (b + s) * terms.inverseA
    // Λ: |Pᵢ|/P₃ is the centre's screen coordinate, |p|·|rᵢ|/P₃ bounds the
    // error of Pᵢ and P₃ in screen units, and ρ/P₃ times the rows the
    // ball's angular size.
    let scale = (pi.magnitude + terms.extent * (axis.length + r3Length)) * terms.inverseP3
    let pad = 0x1p-30 * condition * (1 + scale + scale * scale)
    guard lower.isFinite, upper.isFinite, pad.isFinite else { return nil }
    return (lower - pad, upper + pad)
  }
}
