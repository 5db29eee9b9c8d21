import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// What `raytrace bench` reads from its children's output: the render time
/// and object count of a `--stats` report, and the peer's summary line.
final class BenchmarkTests: XCTestCase {
  let stats = """
    scene: /tmp/a b: c.txt: 6 spheres, 1 planes, 12 triangles, 2 transformed \
    spheres; nearest sphere by culling per tile, nearest triangle by testing \
    each
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

  /// Each row's peak memory is the child's own, as its `--stats` reports
  /// it, even after this process has grown: on Linux, `wait4`'s figure
  /// for a child carries the parent's peak (the bench's, once it has
  /// written the 5·10⁶-triangle mesh, was 1184 MiB for every row after).
  func testPeakMemory_TheChildsOwn() throws {
    XCTAssertEqual(
      Benchmark.peakBytes(inStats: stats + "\npeak memory: 118.2 MiB\n"),
      123_941_683)
    XCTAssertNil(Benchmark.peakBytes(inStats: stats))
    // This process past 256 MiB, every page touched.
    let grown = [UInt8](repeating: 1, count: 256 << 20)
    let folder = NSTemporaryDirectory() + "/peak-\(getpid())"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
    defer { try? FileManager.default.removeItem(atPath: folder) }
    let outcome = try Benchmark.spawn(
      CommandLineTests.executable,
      [
        CommandLineTests.packageRoot + "/scenes/spheres.txt", "--size", "16",
        "16", "--depth", folder + "/d.png", "--stats",
      ])
    XCTAssertEqual(outcome.status, 0, outcome.stderr)
    let own = try XCTUnwrap(
      Benchmark.peakBytes(inStats: outcome.stderr), outcome.stderr)
    XCTAssertGreaterThan(own, 1 << 20)
    XCTAssertLessThan(own, 128 << 20, "a 16×16 render's own peak")
    #if os(Linux)
      XCTAssertGreaterThan(outcome.peakBytes, 256 << 20, "wait4's figure")
    #endif
    XCTAssertEqual(grown[grown.count - 1], 1)
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
