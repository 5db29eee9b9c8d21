import XCTest

@testable import Pipeline
@testable import Geometry
@testable import SceneIO
import TestSupport

/// A render's files encoded in pieces on several threads
/// (`OutputEncoding`) hold the same images as each encoded on its own.
final class OutputEncodingTests: XCTestCase {
  func buffers(width: Int, height: Int) -> RenderBuffers<Double> {
    var generator = SplitMix64(seed: 3)
    let count = width * height
    var depth: [Double] = []
    var normals: [Vector3<Double>] = []
    var color: [RGB<Double>] = []
    for pixel in 0..<count {
      let miss = pixel % 7 == 0
      depth.append(
        miss ? .infinity : Double.random(in: 1...50, using: &generator))
      let normal = Vector3<Double>(
        Double.random(in: -1...1, using: &generator),
        Double.random(in: -1...1, using: &generator), 1
      ).normalized()
      normals.append(miss ? .zero : normal)
      color.append(
        Vector3(
          Double.random(in: -0.1...1.1, using: &generator),
          Double(pixel % 256) / 255, 0.5))
    }
    return RenderBuffers(
      width: width, height: height, depth: depth, normals: normals,
      color: color)
  }

  func testFilesInPiecesHoldTheSameImagesAsEachEncodedWhole() throws {
    // 300 rows of 400 pixels: 1,201 bytes a row, 218 rows a piece, so two
    // pieces an image.
    let buffers = buffers(width: 400, height: 300)
    for style in [ImageStyle.course, .mit] {
      let files = [
        OutputFile(kind: .shaded, path: "s.png")!,
        OutputFile(kind: .depth, path: "d.png")!,
        OutputFile(kind: .normals, path: "n.png")!,
        OutputFile(kind: .normals, path: "n.ppm")!,
        OutputFile(kind: .depth, path: "d.pfm")!,
      ]
      let range = style.depthRange(buffers.depth, given: nil)
      let encoded = OutputEncoding.encode(
        buffers, files: files, style: style, depthRange: range, png: .default)
      XCTAssertEqual(encoded.count, files.count)
      let expected = [
        style.colorImage(buffers), style.depthImage(buffers, range: nil),
        style.normalImage(buffers),
      ]
      for (bytes, image) in zip(encoded, expected) {
        XCTAssertEqual(try PNGDecoder.decode(bytes), image, "\(style)")
      }
      XCTAssertEqual(encoded[3], PPMEncoder.encode(expected[2]))
      XCTAssertEqual(
        encoded[4],
        PFMEncoder.encode(
          RawImage(
            width: 400, height: 300, channels: 1,
            values: buffers.depth.map { Float($0) })))
    }
  }

  func testPixelBuffersAndValuesGiveTheSameRows() {
    // Normals and colours rendered straight into pixels read back as the
    // pixels the values would have given.
    var buffers = buffers(width: 9, height: 5)
    for style in [ImageStyle.course, .mit] {
      let normalRows = style.normalRows(buffers).image
      let colorRows = style.colorRows(buffers).image
      buffers.normalBytes = normalRows.bytes
      buffers.colorBytes = colorRows.bytes
      XCTAssertEqual(style.normalRows(buffers).image, normalRows)
      XCTAssertEqual(style.colorRows(buffers).image, colorRows)
      buffers.normalBytes = []
      buffers.colorBytes = []
      for pixel in [0, 1, 13, 44] {
        let (column, row) = (pixel % 9, pixel / 9)
        XCTAssertTrue(
          normalRows[column, row] == style.pixel(normal: buffers.normals[pixel])
        )
        XCTAssertTrue(
          colorRows[column, row] == style.pixel(buffers.color[pixel]))
      }
    }
  }
}
