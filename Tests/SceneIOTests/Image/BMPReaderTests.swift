import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// The BMP reader on files written here byte by byte: both row orders,
/// 24- and 32-bit, padding, and every refusal.
final class BMPReaderTests: XCTestCase {
  /// A 3×2 image with distinct texels: (column·80, row·100, 7) from the top.
  static let image = Image8(
    width: 3, height: 2,
    bytes: (0..<2).flatMap { row in
      (0..<3).flatMap { column in [UInt8(column * 80), UInt8(row * 100), 7] }
    })

  /// `image` as a BMP file: bottom-up unless `topDown`, rows padded to 4
  /// bytes, a 40-byte info header (or `headerSize`, zero-filled).
  static func bmp(
    _ image: Image8, bits: Int = 24, topDown: Bool = false,
    compression: UInt32 = 0, headerSize: Int = 40, masks: [UInt32] = []
  ) -> [UInt8] {
    let bytesPerPixel = bits / 8
    let stride = (image.width * bytesPerPixel + 3) / 4 * 4
    var pixels: [UInt8] = []
    let rows = Array(0..<image.height)
    for row in topDown ? rows : rows.reversed() {
      var line: [UInt8] = []
      for column in 0..<image.width {
        let (r, g, b) = image[column, row]
        line += [b, g, r]
        if bits == 32 { line.append(255) }
      }
      line += [UInt8](repeating: 0, count: stride - line.count)
      pixels += line
    }
    func le32(_ value: UInt32) -> [UInt8] {
      (0..<4).map { UInt8(truncatingIfNeeded: value >> (8 * $0)) }
    }
    func le16(_ value: UInt16) -> [UInt8] {
      [UInt8(value & 0xFF), UInt8(value >> 8)]
    }
    let maskBytes = masks.flatMap(le32)
    let offset = 14 + headerSize + maskBytes.count
    var info =
      le32(UInt32(headerSize)) + le32(UInt32(bitPattern: Int32(image.width)))
      + le32(UInt32(bitPattern: Int32(topDown ? -image.height : image.height)))
      + le16(1) + le16(UInt16(bits)) + le32(compression)
      + le32(UInt32(pixels.count)) + le32(2835) + le32(2835) + le32(0)
      + le32(0)
    info += [UInt8](repeating: 0, count: headerSize - info.count)
    let header =
      Array("BM".utf8) + le32(UInt32(offset + pixels.count)) + le32(0)
      + le32(UInt32(offset))
    return header + info + maskBytes + pixels
  }

  func testDecode_24Bit_BottomUp() throws {
    XCTAssertEqual(try BMPReader.decode(Self.bmp(Self.image)), Self.image)
  }

  func testDecode_24Bit_TopDown() throws {
    XCTAssertEqual(
      try BMPReader.decode(Self.bmp(Self.image, topDown: true)), Self.image)
  }

  func testDecode_32Bit_BothOrders() throws {
    XCTAssertEqual(
      try BMPReader.decode(Self.bmp(Self.image, bits: 32)), Self.image)
    XCTAssertEqual(
      try BMPReader.decode(Self.bmp(Self.image, bits: 32, topDown: true)),
      Self.image)
  }

  /// 32-bit bit fields in the standard layout, and the longer V4/V5
  /// headers, are read like plain files.
  func testDecode_BitFieldsAndLongHeaders() throws {
    XCTAssertEqual(
      try BMPReader.decode(
        Self.bmp(
          Self.image, bits: 32, compression: 3,
          masks: [0x00FF_0000, 0x0000_FF00, 0x0000_00FF])),
      Self.image)
    XCTAssertEqual(
      try BMPReader.decode(Self.bmp(Self.image, headerSize: 124)), Self.image)
  }

  func assertRefused(
    _ bytes: [UInt8], _ message: String,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    XCTAssertThrowsError(try BMPReader.decode(bytes), file: file, line: line) {
      XCTAssertEqual(
        ($0 as? BMPReader.Failure)?.description, message, file: file,
        line: line)
    }
  }

  func testRefuses_CorruptAndUnsupported() {
    let good = Self.bmp(Self.image)
    assertRefused(
      Array("PK".utf8) + good.dropFirst(2),
      "not a BMP file (it does not start with 'BM')")
    assertRefused(
      Array(good.prefix(30)),
      "truncated BMP header: 30 bytes, at least 54 needed")
    assertRefused(
      Self.bmp(Self.image, headerSize: 64),
      "unsupported BMP info header of 64 bytes (supported: the Windows "
        + "headers of 40, 52, 56, 108 or 124)")
    var eightBit = good
    eightBit[28] = 8
    assertRefused(
      eightBit, "8-bit BMP is not supported (only uncompressed 24- and 32-bit)")
    assertRefused(
      Self.bmp(Self.image, compression: 1),
      "compressed BMP (compression 1) is not supported (only uncompressed)")
    assertRefused(
      Self.bmp(
        Self.image, bits: 32, compression: 3,
        masks: [0x0000_00FF, 0x0000_FF00, 0x00FF_0000]),
      "BMP bit fields other than 8-bit red, green, blue are not supported")
    var zeroWidth = good
    zeroWidth.replaceSubrange(18..<22, with: [0, 0, 0, 0])
    assertRefused(
      zeroWidth, "BMP size 0×2 is out of range (1 to 16384 texels on a side)")
    var planes = good
    planes[26] = 2
    assertRefused(planes, "BMP planes must be 1, found 2")
  }

  /// A file cut anywhere in its pixels, or with its pixel offset past its
  /// end, is an error naming the sizes.
  func testRefuses_Truncated() {
    let good = Self.bmp(Self.image)
    assertRefused(
      Array(good.dropLast()),
      "truncated BMP: 3×2 pixels need 24 bytes from offset 54, the file has "
        + "77 bytes")
    for cut in 54..<good.count {
      XCTAssertThrowsError(try BMPReader.decode(Array(good.prefix(cut))))
    }
    var farOffset = good
    farOffset[10] = 200
    XCTAssertThrowsError(try BMPReader.decode(farOffset))
  }
}
