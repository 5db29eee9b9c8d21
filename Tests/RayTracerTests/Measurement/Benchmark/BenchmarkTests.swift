import XCTest

@testable import FastEngine
@testable import Measurement
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import Numerics
@testable import PlatformSupport

/// What `raytrace bench` reads from its children's output: the render time
/// and object count of a `--stats` report, and the peer's summary line.
final class BenchmarkTests: XCTestCase {
  let stats = """
    scene: /tmp/a b: c.txt: 6 spheres, 1 planes, 12 triangles, 2 transformed \
    spheres; nearest sphere by culling per tile, nearest triangle by testing each
    size: 800x800, 640000 rays, precision double
    render: 0.01629 s, 39.3 Mrays/s
    write: 0.01626 s
    """

  func testRenderSecondsAndObjectsFromStats() {
    XCTAssertEqual(Benchmark.renderSeconds(inStats: stats), 0.01629)
    // A colon in the path does not shift the counts.
    XCTAssertEqual(Benchmark.objectCount(inStats: stats), 21)
    XCTAssertNil(Benchmark.objectCount(inStats: "render: 1 s"))
    XCTAssertNil(Benchmark.objectCount(inStats: "scene: x: many spheres"))
  }

  func testPeerSummaryLine() throws {
    let text = """
      2026-11-26 03:50:00 WARN something about the LLVM backend
      mitsuba llvm_ad_rgb 1920x1080: load 1.130 s, first 0.210 s, \
      median 0.0813 s, 25.5 Mrays/s
      """
    let result = try XCTUnwrap(PeerBenchmark.parse(text))
    XCTAssertEqual(result.variant, "llvm_ad_rgb")
    XCTAssertEqual(result.loadSeconds, 1.13)
    XCTAssertEqual(result.firstSeconds, 0.21)
    XCTAssertEqual(result.medianSeconds, 0.0813)
    XCTAssertEqual(result.megaraysPerSecond, 25.5)
    XCTAssertNil(PeerBenchmark.parse("mitsuba: the scene has no camera"))
    XCTAssertNil(PeerBenchmark.parse(""))
  }

  func testThePeerSkipsOnlyTheLargestSphereScenes() {
    func workload(_ source: Workload.Source) -> Workload {
      Workload(
        name: "w", source: source, width: 8, height: 8, outputs: [.depth])
    }
    XCTAssertTrue(PeerBenchmark.accepts(workload(.randomSpheres(10_000))))
    XCTAssertTrue(PeerBenchmark.accepts(workload(.randomSpheres(100_000))))
    XCTAssertFalse(PeerBenchmark.accepts(workload(.randomSpheres(1_000_000))))
    XCTAssertTrue(PeerBenchmark.accepts(workload(.randomMesh(5_000_000))))
  }

  func testAMissingPeerScriptIsNamedBeforeTheRun() throws {
    let problem = try XCTUnwrap(
      PeerBenchmark.problem(withScript: "/nonexistent/peer_mitsuba.py"))
    XCTAssertTrue(problem.contains("'/nonexistent/peer_mitsuba.py'"), problem)
    XCTAssertNil(PeerBenchmark.problem(withScript: #filePath))
  }

  func testReferenceWorkloadsNeedTheirFolder() {
    let bunny = Workload.standard.first {
      if case .reference = $0.source { return true }
      return false
    }!
    let absent = Benchmark(
      executable: "raytrace", dataFolder: "/tmp", runs: 1,
      referenceFolder: "/nonexistent/folder")
    XCTAssertFalse(absent.isAvailable(bunny))
    XCTAssertTrue(absent.isAvailable(Workload.standard[0]))
    XCTAssertNil(bunny.generatedCount)
  }
}
