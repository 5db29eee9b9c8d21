import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// Renders that share a `SearchCache` (a compiled scene's renders, as
/// `FastScene` makes them) are the renders without one, bit for bit and
/// searched the same way, through a sequence of views that each change
/// one thing the tiles depend on; and a second render of a view reuses
/// the first's tiles rather than building them again.
final class SearchCacheTests: XCTestCase {
  typealias Kernel = StableKernel<Double>

  /// `name` compiled to project its spheres and triangles onto tiles.
  func projected(_ name: String) throws -> CompiledScene<Kernel> {
    let path = "\(ProjectFiles.projectFolder)/scenes/\(name)"
    return CompiledScene(
      try SceneReader.read(
        contentsOf: path, options: SceneOptions(style: .course)),
      hierarchyThreshold: .max, projectionThreshold: 0,
      triangleProjectionThreshold: 0, threads: 2)
  }

  func testCachedRenders_AreFreshRenders() throws {
    func settings(
      _ width: Int, _ height: Int, samples: Int = 1, style: ImageStyle = .course
    ) -> RenderSettings {
      var settings = RenderSettings(
        width: width, height: height, outputs: [.depth, .normals, .shaded],
        style: style, threads: 2)
      settings.samples = samples
      return settings
    }
    // Each step changes one thing the tiles depend on, or nothing; an
    // overlap limit of 0 declines the tiles (the hierarchies then), and
    // the view after it takes tiles again.
    // (The sizes grow: a smaller image's boxes, scaled, would hold a larger
    // one's pixels, and the wrong tiles would give the right image.)
    let steps: [(RenderSettings, overlapLimit: Int)] = [
      (settings(40, 30), 32), (settings(40, 30), 32), (settings(48, 30), 32),
      (settings(48, 36), 32), (settings(48, 36, samples: 4), 32),
      (settings(48, 36, samples: 4, style: .mit), 32),
      (settings(48, 36, samples: 4, style: .mit), 0),
      (settings(48, 36, samples: 4, style: .mit), 0),
      (settings(64, 48), 32),
    ]
    for name in ["spheres.txt", "mesh-and-transforms.txt"] {
      let scene = try projected(name)
      let cache = SearchCache<Kernel>()
      var searches: [Renderer.SphereSearch] = []
      for (step, (settings, limit)) in steps.enumerated() {
        let fresh = Renderer.renderReportingSearch(
          scene, settings: settings, overlapLimit: limit)
        let cached = Renderer.renderReportingSearch(
          scene, settings: settings, overlapLimit: limit, cache: cache)
        XCTAssertEqual(
          cached.buffers.bits, fresh.buffers.bits, "\(name), step \(step)")
        XCTAssertEqual(cached.search, fresh.search, "\(name), step \(step)")
        XCTAssertEqual(
          cached.triangleSearch, fresh.triangleSearch, "\(name), step \(step)")
        searches.append(cached.search)
      }
      // Both ways of searching were exercised.
      XCTAssertEqual(searches.first, .screenTiles, name)
      XCTAssertEqual(searches[6], .hierarchy, name)
    }
  }

  func testSameView_ReusesTheTilesAndTheHierarchy() throws {
    let scene = try projected("mesh-and-transforms.txt")
    let cache = SearchCache<Kernel>()
    let settings = RenderSettings(width: 48, height: 36, outputs: [.depth])
    func address<T>(_ array: [T]?) -> UnsafeRawPointer? {
      array?.withUnsafeBufferPointer { UnsafeRawPointer($0.baseAddress) }
    }
    let first = cache.search(scene, settings: settings, overlapLimit: 32)
    let again = cache.search(scene, settings: settings, overlapLimit: 32)
    XCTAssertNotNil(address(first.tiles?.triangleEntries))
    XCTAssertEqual(
      address(first.tiles?.triangleEntries),
      address(again.tiles?.triangleEntries))
    let declined = cache.search(scene, settings: settings, overlapLimit: 0)
    let declinedAgain = cache.search(scene, settings: settings, overlapLimit: 0)
    XCTAssertNil(declined.tiles)
    XCTAssertNotNil(address(declined.scene.triangleHierarchy?.nodes))
    // Built once: after another view took tiles, too.
    _ = cache.search(scene, settings: settings, overlapLimit: 32)
    let thirdTime = cache.search(scene, settings: settings, overlapLimit: 0)
    for later in [declinedAgain, thirdTime] {
      XCTAssertEqual(
        address(later.scene.triangleHierarchy?.nodes),
        address(declined.scene.triangleHierarchy?.nodes))
    }
  }
}
