import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// A render handed earlier buffers (`recycling`, as repeated renders are)
/// writes every value of them: over buffers filled with one value and over
/// buffers filled with another it gives the buffers a fresh render gives,
/// for every output as values and as 8-bit pixels, single-sample and
/// supersampled.
final class RendererRecyclingTests: XCTestCase {
  func compiled(_ name: String) throws -> CompiledScene<StableKernel<Double>> {
    let path = "\(ProjectFiles.projectFolder)/scenes/\(name)"
    return CompiledScene(
      try SceneReader.read(
        contentsOf: path, options: SceneOptions(style: .course)))
  }

  /// Buffers the size `settings` asks for, every value `mark` (every byte
  /// its low byte).
  func marked(_ settings: RenderSettings, _ mark: Double) -> RenderBuffers<
    Double
  > {
    let count = settings.width * settings.height
    func values(_ output: RenderOutputs) -> Int {
      settings.outputs.contains(output)
        && !settings.quantizedOutputs.contains(output) ? count : 0
    }
    func bytes(_ output: RenderOutputs) -> Int {
      settings.quantizedOutputs.contains(output) ? 3 * count : 0
    }
    var buffers = RenderBuffers<Double>(
      width: settings.width, height: settings.height,
      depth: Array(repeating: mark, count: count),
      normals: Array(
        repeating: Vector3(mark, mark, mark), count: values(.normals)),
      color: Array(repeating: RGB(mark, mark, mark), count: values(.shaded)))
    let byte = UInt8(truncatingIfNeeded: Int(mark))
    buffers.normalBytes = Array(repeating: byte, count: bytes(.normals))
    buffers.colorBytes = Array(repeating: byte, count: bytes(.shaded))
    return buffers
  }

  func testRenderOverMarkedBuffers_IsAFreshRender() throws {
    var checked = 0
    for name in ["spheres.txt", "mesh-and-transforms.txt"] {
      let scene = try compiled(name)
      for quantized in [RenderOutputs(), [.normals, .shaded]] {
        for samples in [1, 4] {
          var settings = RenderSettings(
            width: 48, height: 36, outputs: [.depth, .normals, .shaded],
            threads: 2)
          settings.quantizedOutputs = quantized
          settings.samples = samples
          let label = "\(name), quantized \(quantized.rawValue), \(samples) spp"
          let fresh = Renderer.renderReportingSearch(scene, settings: settings)
          for mark in [-7.0, 92.0] {
            let recycled = Renderer.renderReportingSearch(
              scene, settings: settings, recycling: marked(settings, mark))
            XCTAssertEqual(
              recycled.buffers.bits, fresh.buffers.bits, "\(label), \(mark)")
            checked += 1
          }
        }
      }
    }
    XCTAssertEqual(checked, 16)
  }
}
