import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// Every format the project writes reads back to the same values.
final class ImageFileReaderTests: XCTestCase {
  let image = Image8(
    width: 3, height: 2,
    bytes: [0, 1, 2, 10, 20, 30, 255, 254, 253, 7, 8, 9, 100, 0, 50, 1, 1, 1])

  func testEightBit_PNGAndPPM() throws {
    for bytes in [PNGEncoder.encode(image), PPMEncoder.encode(image)] {
      let read = try ImageFileReader.read(bytes)
      XCTAssertEqual(read, ReadImage(image))
      XCTAssertEqual(read[1, 0, 2], 30)
    }
  }

  func testRawValues_PFMAndNPY() throws {
    let values: [Double] = [1.5, .infinity, -2, 0.25, 1e-3, 7]
    let raw = RawImage<Double>(width: 3, height: 2, channels: 1, values: values)
    let exact = try ImageFileReader.read(NPYEncoder.encode(raw))
    XCTAssertEqual(exact.values, values, "<f8 holds Double's bits")
    for bytes in [
      PFMEncoder.encode(converting: raw),
      NPYEncoder.encode(
        RawImage<Float>(
          width: 3, height: 2, channels: 1, values: values.map(Float.init))),
    ] {
      let read = try ImageFileReader.read(bytes)
      XCTAssertEqual(read.width, 3)
      XCTAssertEqual(read.height, 2)
      XCTAssertEqual(read.channels, 1)
      XCTAssertFalse(read.isEightBit)
      // Float's rounding of each value (PFM and <f4 hold 32 bits).
      XCTAssertEqual(read.values, values.map { Double(Float($0)) })
    }
    let three = RawImage<Double>(
      width: 1, height: 2, channels: 3, values: [1, 2, 3, 4, 5, 6])
    let read = try ImageFileReader.read(NPYEncoder.encode(three))
    XCTAssertEqual(read.values, [1, 2, 3, 4, 5, 6])
    XCTAssertEqual(read[0, 1, 0], 4)
  }

  func testErrors_OneClearReason() {
    func reason(_ bytes: [UInt8]) -> String {
      do {
        _ = try ImageFileReader.read(bytes)
        return "read"
      } catch { return error.description }
    }
    XCTAssertEqual(
      reason(Array("hello".utf8)),
      "not an image in a format it reads (PNG, PPM, PFM, NPY, BMP)")
    XCTAssertEqual(
      reason(Array("P6\n3 2\n255\n".utf8) + [1, 2, 3]),
      "it holds 3 bytes of pixels, not 18")
    XCTAssertEqual(
      reason(Array("P6\n0 2\n255\n".utf8)),
      "its size '0 2' is not two whole numbers from 1 to 32768")
    XCTAssertEqual(reason(Array("PF\n2".utf8)), "its header ends early")
    var npy = NPYEncoder.encode(
      RawImage<Double>(width: 2, height: 2, channels: 1, values: [1, 2, 3, 4]))
    npy.removeLast(8)
    XCTAssertEqual(reason(npy), "it holds 24 bytes of values, not 32")
    // A PNG header claiming 2³²−1 pixels a side: refused before anything
    // is allocated (its row size overflowed, a trap).
    var header: [UInt8] = []
    for value: UInt32 in [0xFFFF_FFFF, 0xFFFF_FFFF] {
      header += withUnsafeBytes(of: value.bigEndian, Array.init)
    }
    header += [8, 2, 0, 0, 0]
    var png = PNGEncoder.encode(Image8(width: 1, height: 1, bytes: [1, 2, 3]))
    // Replace the IHDR's data and its CRC (bytes 16..<29, then 29..<33).
    png.replaceSubrange(16..<29, with: header)
    let crc = PNGEncoder.crc32(Array("IHDR".utf8) + header)
    png.replaceSubrange(
      29..<33, with: withUnsafeBytes(of: crc.bigEndian, Array.init))
    XCTAssertEqual(
      reason(png),
      "not a PNG file it can read: its size 4294967295×4294967295 is beyond "
        + "32768 a side")
  }
}
