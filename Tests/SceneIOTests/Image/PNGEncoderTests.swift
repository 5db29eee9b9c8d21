import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

final class PNGEncoderTests: XCTestCase {
  /// A small image with every kind of row the filters care about: flat,
  /// gradients, noise.
  static func makeImage(width: Int = 13, height: Int = 7, seed: UInt64 = 1)
    -> Image8
  {
    var generator = SplitMix64(seed: seed)
    var bytes: [UInt8] = []
    for row in 0..<height {
      for column in 0..<width {
        switch row % 3 {
        case 0: bytes += [40, 80, 120]
        case 1: bytes += [UInt8(column * 19 % 256), UInt8(row * 31 % 256), 200]
        default:
          bytes += (0..<3).map { _ in
            UInt8.random(in: 0...255, using: &generator)
          }
        }
      }
    }
    return Image8(width: width, height: height, bytes: bytes)
  }

  /// CRC-32 (ISO 3309, the polynomial PNG names) bit by bit, independent of
  /// zlib's table-driven routine that the encoder calls.
  func referenceCRC(_ bytes: [UInt8]) -> UInt32 {
    var crc: UInt32 = 0xFFFF_FFFF
    for byte in bytes {
      crc ^= UInt32(byte)
      for _ in 0..<8 {
        crc = crc & 1 == 1 ? (crc >> 1) ^ 0xEDB8_8320 : crc >> 1
      }
    }
    return ~crc
  }

  struct Chunk {
    var type: String
    var data: [UInt8]
    var crc: UInt32
  }

  static func chunks(_ png: [UInt8]) -> [Chunk] {
    var result: [Chunk] = []
    var offset = 8
    while offset + 12 <= png.count {
      let length = Int(PNGDecoder.readBigEndian(png, offset))
      let type = String(
        decoding: png[(offset + 4)..<(offset + 8)], as: UTF8.self)
      let data = Array(png[(offset + 8)..<(offset + 8 + length)])
      result.append(
        Chunk(
          type: type, data: data,
          crc: PNGDecoder.readBigEndian(png, offset + 8 + length)))
      offset += 12 + length
    }
    XCTAssertEqual(offset, png.count, "bytes left after the last chunk")
    return result
  }

  func testEncode_SignatureAndChunkOrder() {
    let png = PNGEncoder.encode(Self.makeImage())
    XCTAssertEqual(Array(png[0..<8]), [137, 80, 78, 71, 13, 10, 26, 10])
    XCTAssertEqual(Self.chunks(png).map(\.type), ["IHDR", "IDAT", "IEND"])
  }

  func testEncode_HeaderFields() throws {
    let png = PNGEncoder.encode(Self.makeImage(width: 300, height: 2))
    let header = try XCTUnwrap(Self.chunks(png).first)
    XCTAssertEqual(header.data, [0, 0, 1, 44, 0, 0, 0, 2, 8, 2, 0, 0, 0])
  }

  func testEncode_EveryChunkCRCMatchesTheBitwiseReference() {
    for chunk in Self.chunks(PNGEncoder.encode(Self.makeImage())) {
      XCTAssertEqual(
        chunk.crc, referenceCRC(Array(chunk.type.utf8) + chunk.data), chunk.type
      )
    }
  }

  func testReferenceCRC_KnownValue() {
    // The CRC of the IEND chunk (type only, no data) is fixed by the format.
    XCTAssertEqual(referenceCRC(Array("IEND".utf8)), 0xAE42_6082)
  }

  func testEncodeDecode_RoundTripForEveryFilterAndLevel() throws {
    let image = Self.makeImage()
    for filter in PNGFilter.allCases {
      for level: Int32 in [0, 1, 6, 9] {
        let png = PNGEncoder.encode(
          image, options: PNGOptions(compressionLevel: level, filter: filter))
        XCTAssertEqual(
          try PNGDecoder.decode(png), image, "filter \(filter), level \(level)")
      }
    }
  }

  func testEncode_RowsCarryTheChosenFilterType() throws {
    let image = Self.makeImage()
    for (filter, type) in [
      (PNGFilter.none, 0), (.sub, 1), (.up, 2), (.paeth, 4),
    ] {
      let filtered = PNGEncoder.filterRows(image, filter)
      let stride = image.width * 3 + 1
      for row in 0..<image.height {
        XCTAssertEqual(
          Int(filtered[row * stride]), type, "\(filter) row \(row)")
      }
    }
  }

  func testEncode_AdaptivePicksNoneForAFlatFirstRow() {
    // A flat first row costs 0 under sub (all but the first pixel) but its
    // raw bytes are large; with all-zero pixels every filter ties and the
    // first candidate, none, is kept.
    let image = Image8(
      width: 4, height: 2, bytes: [UInt8](repeating: 0, count: 24))
    let filtered = PNGEncoder.filterRows(image, .adaptive)
    XCTAssertEqual(filtered[0], 0)
    XCTAssertEqual(filtered[13], 0)
  }

  func testEncode_OnePixelImage() throws {
    let image = Image8(width: 1, height: 1, bytes: [1, 2, 3])
    XCTAssertEqual(try PNGDecoder.decode(PNGEncoder.encode(image)), image)
  }

  func testDecode_RejectsACorruptedCRC() {
    var png = PNGEncoder.encode(Self.makeImage())
    png[png.count - 20] ^= 0xFF  // inside IDAT
    XCTAssertThrowsError(try PNGDecoder.decode(png))
  }

  func testDecode_RejectsATruncatedFile() {
    let png = PNGEncoder.encode(Self.makeImage())
    XCTAssertThrowsError(
      try PNGDecoder.decode(Array(png.prefix(png.count - 5))))
  }

  func testPaeth_PicksTheNearestNeighbour() {
    XCTAssertEqual(PNGEncoder.paeth(10, 20, 10), 20)  // p = 20: above
    XCTAssertEqual(PNGEncoder.paeth(20, 10, 10), 20)  // p = 20: left
    XCTAssertEqual(PNGEncoder.paeth(10, 10, 30), 10)  // p = -10: ties go left
  }
}
