import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

final class RawEncoderTests: XCTestCase {
  func testPPM_HeaderThenBytes() {
    let image = Image8(width: 2, height: 1, bytes: [1, 2, 3, 4, 5, 6])
    XCTAssertEqual(
      PPMEncoder.encode(image),
      Array("P6\n2 1\n255\n".utf8) + [1, 2, 3, 4, 5, 6])
  }

  func testPFM_OneChannelBottomRowFirstLittleEndian() {
    let image = RawImage<Float>(
      width: 2, height: 2, channels: 1, values: [1, 2, .infinity, -0.5])
    let bytes = PFMEncoder.encode(image)
    let header = Array("Pf\n2 2\n-1.0\n".utf8)
    XCTAssertEqual(Array(bytes.prefix(header.count)), header)
    let body = Array(bytes.dropFirst(header.count))
    XCTAssertEqual(body.count, 16)
    // Bottom row (inf, -0.5) comes first.
    XCTAssertEqual(Array(body[0..<4]), [0x00, 0x00, 0x80, 0x7F])  // +inf
    XCTAssertEqual(Array(body[4..<8]), [0x00, 0x00, 0x00, 0xBF])  // -0.5
    XCTAssertEqual(Array(body[8..<12]), [0x00, 0x00, 0x80, 0x3F])  // 1
    XCTAssertEqual(Array(body[12..<16]), [0x00, 0x00, 0x00, 0x40])  // 2
  }

  func testPFM_ThreeChannels() {
    let image = RawImage<Float>(
      width: 1, height: 1, channels: 3, values: [0, 0, 1])
    let bytes = PFMEncoder.encode(image)
    let header = Array("PF\n1 1\n-1.0\n".utf8)
    XCTAssertEqual(Array(bytes.prefix(header.count)), header)
    XCTAssertEqual(
      Array(bytes.dropFirst(header.count)),
      [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x80, 0x3F])
  }

  /// A Double image's values rounded to Float once each as written: the
  /// bytes of the image converted first.
  func testPFM_DoubleValuesRoundedOnce() {
    let values: [Double] = [0.1, 1e300, -1e-50, .infinity, -2.5, 1 / 3]
    let image = RawImage<Double>(
      width: 1, height: 2, channels: 3, values: values)
    XCTAssertEqual(
      PFMEncoder.encode(converting: image),
      PFMEncoder.encode(
        RawImage<Float>(
          width: 1, height: 2, channels: 3, values: values.map { Float($0) })))
    // The top row comes last, and its last value, −10⁻⁵⁰, is −0 in Float.
    XCTAssertEqual(
      Array(PFMEncoder.encode(converting: image).suffix(4)),
      [0x00, 0x00, 0x00, 0x80])
  }

  func npyHeader(_ bytes: [UInt8]) -> (String, Int) {
    let length = Int(bytes[8]) | Int(bytes[9]) << 8
    return (
      String(decoding: bytes[10..<(10 + length)], as: UTF8.self), 10 + length
    )
  }

  func testNPY_FloatHeaderAlignedAndValues() {
    let image = RawImage<Float>(
      width: 3, height: 2, channels: 1, values: [1, 2, 3, 4, 5, 6])
    let bytes = NPYEncoder.encode(image)
    XCTAssertEqual(Array(bytes[0..<8]), [0x93] + Array("NUMPY".utf8) + [1, 0])
    let (header, dataStart) = npyHeader(bytes)
    XCTAssertEqual(dataStart % 64, 0, "data must start on a 64-byte boundary")
    XCTAssertTrue(
      header.hasPrefix(
        "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }"))
    XCTAssertTrue(header.hasSuffix("\n"))
    XCTAssertEqual(bytes.count - dataStart, 24)
    XCTAssertEqual(
      Array(bytes[dataStart..<(dataStart + 4)]), [0, 0, 0x80, 0x3F])
  }

  func testNPY_DoubleWithChannels() {
    let image = RawImage<Double>(
      width: 1, height: 1, channels: 3, values: [0, 1, -2])
    let bytes = NPYEncoder.encode(image)
    let (header, dataStart) = npyHeader(bytes)
    XCTAssertTrue(header.contains("'descr': '<f8'"))
    XCTAssertTrue(header.contains("'shape': (1, 1, 3)"))
    XCTAssertEqual(bytes.count - dataStart, 24)
    XCTAssertEqual(
      Array(bytes[(dataStart + 8)..<(dataStart + 16)]),
      [0, 0, 0, 0, 0, 0, 0xF0, 0x3F])
  }

  func testImageFormat_FromExtension() {
    XCTAssertEqual(ImageFormat(path: "out.png"), .png)
    XCTAssertEqual(ImageFormat(path: "dir.v2/out.PPM"), .ppm)
    XCTAssertEqual(ImageFormat(path: "a.pfm"), .pfm)
    XCTAssertEqual(ImageFormat(path: "a.npy"), .npy)
    XCTAssertNil(ImageFormat(path: "out.jpg"))
    XCTAssertNil(ImageFormat(path: "dir.png/out"))
    XCTAssertNil(ImageFormat(path: "noextension"))
  }

  /// A large image's rows converted by several threads, each a band, are
  /// the bytes one thread writes (bottom row first), in both channel counts.
  func testPFM_InPartsAsOneThread() {
    let (width, height) = (301, 457)
    for channels in [1, 3] {
      let values = (0..<(width * height * channels)).map {
        Double($0 % 1_000) * 0.37 - Double($0 / 7_000)
      }
      values.withUnsafeBufferPointer { values in
        let one = PFMEncoder.encode(
          width: width, height: height, channels: channels, values: values)
        for threads in [2, 3, 16] {
          XCTAssertEqual(
            PFMEncoder.encode(
              width: width, height: height, channels: channels,
              values: values, threads: threads),
            one, "\(channels) channels, \(threads) threads")
        }
      }
    }
  }
}
