import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// How depth becomes 8-bit levels in each style.
final class ImageConventionsTests: XCTestCase {
  /// The course's depth level is 255 − ⌊255·f⌋ with f = (t − near)/(far −
  /// near): inverted after truncation, so wherever 255·f is not whole it is
  /// one level above truncating 1 − f (which the style once did, and which
  /// this test tells apart at every level).
  func testDepthImage_CourseInvertsAfterTruncating() {
    // near 1, far 1 + 255/16: t = 1 + (k + 0.5)/16 (exact) gives 255·f
    // within a rounding or two of k + 0.5, far from either whole number.
    var depth: [Double] = [1, 1 + 255.0 / 16]
    for k in 0..<255 { depth.append(1 + (Double(k) + 0.5) / 16) }
    depth += [.infinity, 50]  // a miss; a hit past the course's cutoff
    let buffers = RenderBuffers<Double>(
      width: depth.count, height: 1, depth: depth)
    let image = ImageStyle.course.depthImage(buffers, range: nil)
    let levels = (0..<depth.count).map { image.bytes[3 * $0] }
    XCTAssertEqual(levels[0], 255, "nearest hit white")
    XCTAssertEqual(levels[1], 0, "farthest hit black")
    for k in 0..<255 {
      XCTAssertEqual(
        levels[2 + k], UInt8(255 - k), "255·f = \(k).5: 255 − \(k)")
      XCTAssertNotEqual(
        levels[2 + k], ImageStyle.course.quantize(1 - (Double(k) + 0.5) / 255),
        "one level above truncating 1 − f at \(k).5")
    }
    XCTAssertEqual(levels[257], 0, "miss black")
    XCTAssertEqual(levels[258], 0, "beyond the cutoff black")
  }

  /// The mit style rounds f itself over the range it is given, clamped.
  func testDepthImage_MitRoundsTheGivenRange() {
    let buffers = RenderBuffers<Double>(
      width: 4, height: 1, depth: [8, 13, 18, 30])
    let image = ImageStyle.mit.depthImage(buffers, range: 8...18)
    XCTAssertEqual(
      (0..<4).map { image.bytes[3 * $0] }, [0, 128, 255, 255],
      "near black, 127.5 rounds up, far and beyond white")
  }

  /// Normals and colours rendered straight into 8-bit pixels
  /// (`RenderSettings.quantizedOutputs`) are the images made from the
  /// values, byte for byte: every project scene, both styles, one sample
  /// and supersampled, spheres through screen tiles and triangles too.
  func testQuantizedOutputs_SameImagesAsFromValues() throws {
    let scenes = try ProjectFiles.projectScenes()
    // Half the scenes in each style unless RAYTRACE_LONG_TESTS.
    for (half, style) in ImageStyle.allCases.enumerated() {
      for path in Self.quickCases(scenes, half: half % 2) {
        let scene = try SceneReader.read(
          contentsOf: path, options: SceneOptions(style: style))
        for samples in [1, 4] {
          var settings = RenderSettings(
            width: 23, height: 17, outputs: [.depth, .normals, .shaded],
            style: style, threads: 2)
          settings.samples = samples
          let compiled = CompiledScene<StableKernel<Double>>(
            scene, projectionThreshold: 0, triangleProjectionThreshold: 0)
          let values = Renderer.render(compiled, settings: settings)
          settings.quantizedOutputs = [.normals, .shaded]
          let pixels = Renderer.render(compiled, settings: settings)
          XCTAssertTrue(pixels.normals.isEmpty && pixels.color.isEmpty)
          XCTAssertEqual(pixels.depth, values.depth)
          let label = "\(path) \(style) \(samples) samples"
          XCTAssertEqual(
            style.normalImage(pixels).bytes, style.normalImage(values).bytes,
            label)
          XCTAssertEqual(
            style.colorImage(pixels).bytes, style.colorImage(values).bytes,
            label)
        }
      }
    }
  }

  /// `PixelFilter.reach`, which widens culling pyramids and screen boxes
  /// for supersampled rays, bounds every sample's offset and is reached.
  func testPixelFilterReach_BoundsEveryOffset() {
    for filter in PixelFilter.allCases {
      var largest = 0.0
      for step in 0..<100_000 {
        let offset = filter.offset(Double(step) / 100_000).magnitude
        XCTAssertLessThanOrEqual(offset, filter.reach, "\(filter)")
        largest = Swift.max(largest, offset)
      }
      XCTAssertEqual(largest, filter.reach, "\(filter)")
    }
  }
}
