@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import CZlib
import TestSupport
import XCTest

/// The image data compressed in pieces (`PNGEncoder.Pieces`): every cut of
/// the rows must give the same pixels as one stream, and a zlib stream that
/// zlib itself accepts (header, joined deflate data, combined checksum).
final class PNGEncoderPiecesTests: XCTestCase {
  /// The whole zlib stream of a PNG's IDAT chunks, inflated by zlib, which
  /// checks the header's check bits and the Adler-32 at the end.
  func inflate(_ png: [UInt8]) throws -> [UInt8] {
    let data = PNGEncoderTests.chunks(png).filter { $0.type == "IDAT" }.flatMap(
      \.data)
    var length = uLongf(64 << 20)
    var out = [UInt8](repeating: 0, count: Int(length))
    let status = uncompress(&out, &length, data, uLong(data.count))
    XCTAssertEqual(status, Z_OK, "zlib rejected the stream")
    return Array(out.prefix(Int(length)))
  }

  func testEveryCutOfTheRowsDecodesToTheImage() throws {
    try skipUnlessLongTests()
    try checkEveryCut(width: 17, levels: [-1, 0, 1, 6, 9])
  }

  /// Rows of 12,001 filtered bytes: a batch for zlib (`batchBytes`) holds
  /// two, so pieces of 3, 5 and 11 rows end on part of a batch.
  func testPiecesOfSeveralBatchesDecodeToTheImage() throws {
    XCTAssertEqual(PNGEncoder.Pieces.batchBytes / 12_001, 2)
    try checkEveryCut(width: 4_000, levels: [1])
  }

  func checkEveryCut(width: Int, levels: [Int32]) throws {
    let image = PNGEncoderTests.makeImage(width: width, height: 11)
    for filter in PNGFilter.allCases {
      for level in levels {
        let sizes = runsLongTests ? [1, 2, 3, 5, 10, 11, 100] : [1, 11]
        for rowsPerPiece in sizes {
          let pieces = PNGEncoder.Pieces(
            PixelRows(image),
            options: PNGOptions(compressionLevel: level, filter: filter),
            rowsPerPiece: rowsPerPiece)
          XCTAssertEqual(pieces.count, (11 + rowsPerPiece - 1) / rowsPerPiece)
          // Compressed out of order, as threads may finish them.
          var compressed = [PNGEncoder.Pieces.Compressed?](
            repeating: nil, count: pieces.count)
          for index in (0..<pieces.count).reversed() {
            compressed[index] = pieces.compress(index)
          }
          let png = pieces.assemble(compressed.map { $0! })
          let label = "\(filter), level \(level), \(rowsPerPiece) rows a piece"
          XCTAssertEqual(try PNGDecoder.decode(png), image, label)
          // The filtered rows are those of the whole image at once: a
          // piece's first row is filtered against the row before it.
          XCTAssertEqual(
            try inflate(png), PNGEncoder.filterRows(image, filter), label)
        }
      }
    }
  }

  func testOnePieceForAnImageWithoutRows() throws {
    let rows = PixelRows(width: 4, height: 0) { _, _ in
      XCTFail("no row to ask for")
    }
    let pieces = PNGEncoder.Pieces(rows, options: .default)
    XCTAssertEqual(pieces.count, 1)
    let png = pieces.assemble([pieces.compress(0)])
    XCTAssertEqual(try inflate(png), [])
  }

  func testZlibHeaderCheckBitsAndLevelField() {
    for level: Int32 in -1...9 {
      let header = PNGEncoder.Pieces.zlibHeader(level: level)
      XCTAssertEqual(header[0], 0x78, "deflate, 32 KiB window")
      XCTAssertEqual(
        (Int(header[0]) << 8 | Int(header[1])) % 31, 0, "level \(level)")
      XCTAssertEqual(header[1] & 0x20, 0, "no preset dictionary")
    }
    // zlib's own header for the same levels (compress2 writes it).
    for level: Int32 in [0, 1, 2, 5, 6, 7, 9] {
      var length = compressBound(1)
      var out = [UInt8](repeating: 0, count: Int(length))
      _ = compress2(&out, &length, [7], 1, level)
      XCTAssertEqual(
        PNGEncoder.Pieces.zlibHeader(level: level), Array(out.prefix(2)),
        "level \(level)")
    }
  }

  func testLargeImagesAreCutIntoPiecesOfAboutTheTargetSize() {
    let rows = PixelRows(width: 800, height: 800) { _, out in
      out.update(repeating: 0)
    }
    let pieces = PNGEncoder.Pieces(rows, options: .default)
    // 256 KiB over 2,401 bytes a row: 109 rows a piece, 8 pieces.
    XCTAssertEqual(pieces.rowsPerPiece, 109)
    XCTAssertEqual(pieces.count, 8)
  }
}
