import Foundation
import XCTest

@testable import Measurement
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// What a run may do to files: outputs all or none, never over the scene
/// or what it reads, nothing left behind by a signal, names escaped.
final class OutputSafetyTests: XCTestCase {
  var folder = ""

  override func setUpWithError() throws {
    folder = NSTemporaryDirectory() + "raytrace-out-\(UUID().uuidString)"
    try FileManager.default.createDirectory(
      atPath: folder, withIntermediateDirectories: true)
  }

  override func tearDownWithError() throws {
    try? FileManager.default.removeItem(atPath: folder)
  }

  func files() -> [String] {
    ((try? FileManager.default.contentsOfDirectory(atPath: folder)) ?? [])
      .sorted()
  }

  func read(_ name: String) throws -> [UInt8] {
    Array(try Data(contentsOf: URL(fileURLWithPath: folder + "/" + name)))
  }

  /// Starts `raytrace` with `arguments` in the package's folder, through
  /// `sh -c` when `shell` prefixes it (a ulimit, say).
  func start(_ arguments: [String], shell: String? = nil) throws -> Process {
    let process = Process()
    if let shell {
      process.executableURL = URL(fileURLWithPath: "/bin/sh")
      process.arguments =
        ["-c", shell + " exec \"$0\" \"$@\"", CommandLineTests.executable]
        + arguments
    } else {
      process.executableURL = URL(
        fileURLWithPath: CommandLineTests.executable)
      process.arguments = arguments
    }
    process.currentDirectoryURL = URL(
      fileURLWithPath: CommandLineTests.packageRoot)
    process.standardError = Pipe()
    process.standardOutput = Pipe()
    try process.run()
    return process
  }

  func finish(_ process: Process) -> (status: Int32, stderr: String) {
    let pipe = process.standardError as? Pipe
    let data = pipe?.fileHandleForReading.readDataToEndOfFile() ?? Data()
    process.waitUntilExit()
    return (process.terminationStatus, String(decoding: data, as: UTF8.self))
  }

  func run(_ arguments: [String], shell: String? = nil) throws
    -> (status: Int32, stderr: String)
  {
    finish(try start(arguments, shell: shell))
  }

  /// A render long enough (seconds, even in release) to be signalled while
  /// its temporary files exist, which is from before the render starts.
  func interruptMidRender(with signal: Int32, shell: String? = nil) throws {
    try AtomicFile.write([1, 2, 3], to: folder + "/old.png")
    let process = try start(
      [
        "scenes/spheres.txt", "--size", "8000", "8000", "--threads", "1", "-o",
        folder + "/big.png", "--normals", folder + "/old.png",
      ], shell: shell)
    var waited = 0
    while !files().contains(where: { $0.hasPrefix(".rt-") }) && waited < 400 {
      usleep(25_000)
      waited += 1
    }
    XCTAssertTrue(
      files().contains { $0.hasPrefix(".rt-") }, "temporary files exist")
    kill(process.processIdentifier, signal)
    let (_, stderr) = finish(process)
    XCTAssertEqual(process.terminationReason, .uncaughtSignal)
    XCTAssertEqual(process.terminationStatus, signal)
    XCTAssertFalse(stderr.contains("crashed"), stderr)
    XCTAssertEqual(files(), ["old.png"], "no new or temporary file remains")
    XCTAssertEqual(try read("old.png"), [1, 2, 3], "the old file is intact")
  }

  func testInterrupt_LeavesNoFileBehind() throws {
    try interruptMidRender(with: SIGINT)
  }

  /// Ctrl-\ ends the run as Ctrl-C does, without the runtime's crash report.
  func testQuit_LeavesNoFileBehindAndNoCrashReport() throws {
    try interruptMidRender(with: SIGQUIT)
  }

  func testTerminate_LeavesNoFileBehind() throws {
    try interruptMidRender(with: SIGTERM)
  }

  /// Past the file-size limit SIGXFSZ ends the run as it would any
  /// program, after removing its temporary files; the old output is
  /// intact.
  func testFileSizeLimit_EndsByItsSignalCleanly() throws {
    try AtomicFile.write([1, 2, 3], to: folder + "/o.ppm")
    let process = try start(
      ["scenes/spheres.txt", "--size", "200", "200", "-o", folder + "/o.ppm"],
      shell: "ulimit -c 0; ulimit -f 8;")
    _ = finish(process)
    XCTAssertEqual(process.terminationReason, .uncaughtSignal)
    XCTAssertEqual(process.terminationStatus, SIGXFSZ)
    XCTAssertEqual(files(), ["o.ppm"])
    XCTAssertEqual(try read("o.ppm"), [1, 2, 3])
  }

  /// The other signals whose default ends a process: the user signals, the
  /// timers, the CPU-time limit, a closed pipe. (Half of them unless
  /// RAYTRACE_LONG_TESTS.)
  func testEveryTerminatingSignal_LeavesNoFileBehind() throws {
    let signals = [
      SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGVTALRM, SIGPROF, SIGPIPE, SIGHUP,
    ]
    for signal in Self.quickCases(signals) {
      try interruptMidRender(with: signal, shell: "ulimit -c 0;")
      try FileManager.default.removeItem(atPath: folder + "/old.png")
    }
  }

  /// A signal ignored by the parent (`nohup`, `cmd &` in a script) stays
  /// ignored: the render goes on and writes its image.
  func testSignalIgnoredByTheParent_StaysIgnored() throws {
    let process = try start(
      [
        "scenes/spheres.txt", "--size", "600", "600", "--threads", "1",
        "-o", folder + "/o.png",
      ], shell: "trap '' HUP INT;")
    var waited = 0
    while !files().contains(where: { $0.hasPrefix(".rt-") }) && waited < 400 {
      usleep(25_000)
      waited += 1
    }
    kill(process.processIdentifier, SIGHUP)
    kill(process.processIdentifier, SIGINT)
    let (status, stderr) = finish(process)
    XCTAssertEqual(process.terminationReason, .exit, stderr)
    XCTAssertEqual(status, 0, stderr)
    XCTAssertEqual(files(), ["o.png"])
  }

  /// Temporaries left by killed runs (any `.rt-*.tmp`, the old names of
  /// process ids included) never block a later run: each run takes fresh
  /// random names, created exclusively.
  func testLeftoverTemporaries_DoNotBlock() throws {
    var leftovers: [String] = []
    for pid in [1, 2, Int(getpid()), 4_194_304] {
      for number in 0..<3 { leftovers.append(".rt-\(pid)-\(number).tmp") }
    }
    for name in leftovers {
      try AtomicFile.write([9], to: folder + "/" + name)
    }
    let (status, stderr) = try run([
      "scenes/spheres.txt", "--size", "20", "20", "-o", folder + "/o.png",
      "--depth", folder + "/d.png",
    ])
    XCTAssertEqual(status, 0, stderr)
    XCTAssertEqual(files(), (leftovers + ["d.png", "o.png"]).sorted())
    let names = Set(
      (0..<200).map { _ in OutputBatch.temporaryPath(for: "a/b.png") })
    XCTAssertEqual(names.count, 200, "random names")
    XCTAssertTrue(names.allSatisfy { $0.hasPrefix("a/.rt-") && $0.count == 26 })
  }

  /// Two spellings of one file are refused before rendering.
  func testTwoSpellingsOfOneOutput_AreAUsageError() throws {
    let (status, stderr) = try run([
      "scenes/spheres.txt", "--size", "8", "8", "--depth", folder + "/d.png",
      "--normals", folder + "/./d.png",
    ])
    XCTAssertEqual(status, 64, stderr)
    XCTAssertTrue(stderr.contains("name the same file"), stderr)
    XCTAssertEqual(files(), [])
  }

  /// An output may name neither the scene nor a file the scene reads,
  /// however spelled: the scene and its mesh are named here with image
  /// extensions, which the content decides for scenes and meshes.
  func testOutputOverTheSceneOrItsMesh_IsAUsageError() throws {
    let scene = """
      PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }
      Group { numObjects 1 TriangleMesh { obj_file mesh.ppm } }

      """
    try Array(scene.utf8).write(to: folder + "/scene.ppm")
    let mesh = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n"
    try Array(mesh.utf8).write(to: folder + "/mesh.ppm")
    let name = (folder as NSString).lastPathComponent
    let overScene = try run([
      folder + "/scene.ppm", "-o", folder + "/../" + name + "/scene.ppm",
    ])
    XCTAssertEqual(overScene.status, 64, overScene.stderr)
    XCTAssertTrue(overScene.stderr.contains("scene file"), overScene.stderr)
    let overMesh = try run([
      folder + "/scene.ppm", "--size", "8", "8", "-o", folder + "/o.png",
      "--depth", folder + "/./mesh.ppm",
    ])
    XCTAssertEqual(overMesh.status, 64, overMesh.stderr)
    XCTAssertTrue(
      overMesh.stderr.contains("which the scene reads"), overMesh.stderr)
    XCTAssertEqual(files(), ["mesh.ppm", "scene.ppm"], "nothing written")
    XCTAssertEqual(try read("scene.ppm"), Array(scene.utf8))
    XCTAssertEqual(try read("mesh.ppm"), Array(mesh.utf8))
  }

  /// A mesh named with a control character is quoted escaped.
  func testMeshErrorNames_AreEscaped() throws {
    let scene = folder + "/scene.txt"
    try Array(
      """
      PerspectiveCamera { center 0 0 5 direction 0 0 -1 up 0 1 0 angle 30 }
      Group { numObjects 1 TriangleMesh { obj_file "bad\u{1B}[31m.obj" } }

      """.utf8
    ).write(to: scene)
    try Array("v 0 0 0\nf 1 2 3\n".utf8).write(
      to: folder + "/bad\u{1B}[31m.obj")
    let (status, stderr) = try run([scene, "-o", folder + "/o.png"])
    XCTAssertEqual(status, 1, stderr)
    XCTAssertFalse(stderr.contains("\u{1B}"), stderr)
    XCTAssertTrue(stderr.contains("\\u{1B}"), stderr)
  }
}

extension Array where Element == UInt8 {
  fileprivate func write(to path: String) throws {
    try Data(self).write(to: URL(fileURLWithPath: path))
  }
}
