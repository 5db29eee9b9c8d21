import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The tile lists do not depend on how many threads sorted them: each
/// tile lists its primitives in the primitives' order, whatever the parts.
final class TileListsTests: XCTestCase {
  struct Entry: Equatable {
    var index: Int
    var columns: (UInt16, UInt16)
    var rows: (UInt8, UInt8)
    static func == (a: Entry, b: Entry) -> Bool {
      a.index == b.index && a.columns == b.columns && a.rows == b.rows
    }
  }

  /// Random boxes over a 1000×600 image (some empty, some off the edges
  /// clipped, some spanning many tiles), enough for several parts.
  func randomBoxes(count: Int, seed: UInt64) -> [PixelBox] {
    var generator = SplitMix64(seed: seed)
    return (0..<count).map { _ in
      if Int.random(in: 0..<50, using: &generator) == 0 { return .empty }
      let column = Int32.random(in: 0..<1000, using: &generator)
      let row = Int32.random(in: 0..<600, using: &generator)
      let wide = Int.random(in: 0..<100, using: &generator) == 0
      let width = Int32.random(in: 0..<(wide ? 700 : 12), using: &generator)
      let height = Int32.random(in: 0..<(wide ? 300 : 6), using: &generator)
      return PixelBox(
        firstColumn: column, lastColumn: min(999, column + width),
        firstRow: row, lastRow: min(599, row + height))
    }
  }

  func sorted(_ boxes: [PixelBox], threads: Int)
    -> (starts: [Int], entries: [Entry], area: Int?)
  {
    var lists = TileLists<Entry>(tilesAcross: 4, width: 1000, height: 600)
    let area = lists.sort(
      count: boxes.count, threads: threads, areaLimit: .infinity,
      box: { boxes[$0] },
      entry: { Entry(index: $0, columns: $1, rows: $2) })
    return (lists.starts, lists.entries, area)
  }

  func testAnyThreadCount_SameLists() {
    // 2¹⁴ and more primitives are sorted in parts; 100,000 of them make
    // up to 12 parts of at least 2¹³.
    let boxes = randomBoxes(count: 100_000, seed: 0x711E)
    let one = sorted(boxes, threads: 1)
    XCTAssertNotNil(one.area)
    XCTAssertGreaterThan(one.entries.count, boxes.count)
    for threads in [2, 3, 7, 16] {
      let many = sorted(boxes, threads: threads)
      XCTAssertEqual(many.area, one.area, "\(threads) threads: area")
      XCTAssertEqual(many.starts, one.starts, "\(threads) threads: starts")
      XCTAssertTrue(
        many.entries == one.entries, "\(threads) threads: entries differ")
    }
    // Within each tile, the primitives in their order.
    for tile in 0..<(one.starts.count - 1) {
      let indices = one.entries[one.starts[tile]..<one.starts[tile + 1]]
        .map(\.index)
      XCTAssertEqual(indices, indices.sorted(), "tile \(tile) out of order")
    }
  }
}
