import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

final class AtomicFileTests: XCTestCase {
  var folder = ""

  override func setUpWithError() throws {
    var template = Array("/tmp/raytrace-atomic-XXXXXX".utf8CString)
    let made = template.withUnsafeMutableBufferPointer { buffer in
      buffer.baseAddress.flatMap { mkdtemp($0) }.map { String(cString: $0) }
    }
    folder = try XCTUnwrap(made, "mkdtemp failed")
  }

  override func tearDown() {
    for name in contents() { unlink(folder + "/" + name) }
    rmdir(folder)
  }

  func contents() -> [String] { Platform.names(in: folder) }

  func read(_ path: String) -> [UInt8]? {
    try? readFile(path)
  }

  func testWrite_CreatesTheFileAndLeavesNoTemporary() throws {
    try AtomicFile.write([1, 2, 3], to: folder + "/a.bin")
    XCTAssertEqual(read(folder + "/a.bin"), [1, 2, 3])
    XCTAssertEqual(contents(), ["a.bin"])
  }

  func testWrite_ReplacesAnExistingFileWhole() throws {
    try AtomicFile.write(Array(repeating: 7, count: 100), to: folder + "/a.bin")
    try AtomicFile.write([9], to: folder + "/a.bin")
    XCTAssertEqual(read(folder + "/a.bin"), [9])
  }

  func testWriteAll_AFailingTargetLeavesTheOthersUntouched() throws {
    try AtomicFile.write([1], to: folder + "/keep.bin")
    XCTAssertThrowsError(
      try AtomicFile.writeAll([
        ([2], folder + "/keep.bin"), ([3], folder + "/missing/x.bin"),
      ]))
    XCTAssertEqual(
      read(folder + "/keep.bin"), [1], "the first file must not be replaced")
    XCTAssertEqual(contents(), ["keep.bin"], "no temporary may be left behind")
  }

  func testCheckWritable_AcceptsANewFileAndLeavesNothing() throws {
    try AtomicFile.checkWritable(folder + "/new.png")
    XCTAssertEqual(contents(), [])
  }

  func testCheckWritable_RefusesAMissingFolderADirectoryAndAReadOnlyFolder()
    throws
  {
    XCTAssertThrowsError(
      try AtomicFile.checkWritable(folder + "/no/such/dir.png")
    ) {
      XCTAssertEqual(
        ($0 as? OutputError)?.description,
        "cannot write '\(folder)/no/such/dir.png': No such file or directory")
    }
    XCTAssertThrowsError(try AtomicFile.checkWritable(folder)) {
      XCTAssertEqual(($0 as? OutputError)?.reason, "it is a directory")
    }
    if getuid() != 0 {  // root writes anywhere
      chmod(folder, 0o500)
      defer { chmod(folder, 0o700) }
      XCTAssertThrowsError(try AtomicFile.checkWritable(folder + "/x.png"))
    }
  }

  /// Short names in the target's folder, whatever the target's name, so
  /// that a name the folder accepts always leaves room for them.
  func testTemporaryPath_StaysInTheTargetsFolderAndIsShort() {
    let prefix = ".rt-"
    let nested = OutputBatch.temporaryPath(for: "a/b/c.png")
    XCTAssertTrue(nested.hasPrefix("a/b/" + prefix), nested)
    XCTAssertTrue(nested.hasSuffix(".tmp"), nested)
    let plain = OutputBatch.temporaryPath(for: "c.png")
    XCTAssertTrue(plain.hasPrefix(prefix), plain)
    XCTAssertNotEqual(plain, OutputBatch.temporaryPath(for: "c.png"))
    XCTAssertLessThanOrEqual(
      OutputBatch.temporaryPath(for: String(repeating: "n", count: 255)).utf8
        .count, 40)
  }

  /// A 250-byte name (legal: NAME_MAX is 255) is written.
  func testWrite_LongestNames() throws {
    let name = String(repeating: "x", count: 246) + ".png"
    try AtomicFile.write([5], to: folder + "/" + name)
    XCTAssertEqual(contents(), [name])
  }

  /// The temporaries exist from the batch's creation (so through a render)
  /// and are gone once it is committed or abandoned.
  func testBatch_TemporariesLiveUntilCommitOrAbandon() throws {
    let batch = try OutputBatch(paths: [folder + "/a.png", folder + "/b.png"])
    XCTAssertEqual(contents().filter { $0.hasPrefix(".rt-") }.count, 2)
    try batch.commit([[1], [2]])
    XCTAssertEqual(contents(), ["a.png", "b.png"])
    let abandoned = try OutputBatch(paths: [folder + "/c.png"])
    XCTAssertEqual(contents().count, 3)
    abandoned.abandon()
    XCTAssertEqual(contents(), ["a.png", "b.png"])
  }

  /// A rename that fails part way puts back what the earlier ones
  /// replaced: an old target its old bytes, a new target removed.
  func testBatch_FailedRenameRestoresEveryTarget() throws {
    try AtomicFile.write([1], to: folder + "/old.png")
    let renames = AtomicCounter(0)
    var operations = OutputBatch.FileOperations.system
    operations.rename = { from, to in
      // The third rename (b.png's) fails; renames back always work.
      if !from.contains(".rt-") || renames.add(1).new != 3 {
        return OutputBatch.FileOperations.system.rename(from, to)
      }
      errno = EPERM
      return -1
    }
    let batch = try OutputBatch(
      paths: [folder + "/old.png", folder + "/new.png", folder + "/b.png"],
      operations: operations)
    XCTAssertThrowsError(try batch.commit([[7], [8], [9]])) { error in
      XCTAssertEqual((error as? OutputError)?.path, folder + "/b.png")
    }
    XCTAssertEqual(contents(), ["old.png"], "no new file and no temporary")
    XCTAssertEqual(read(folder + "/old.png"), [1], "the old bytes are back")
  }

  /// Without hard links the batch still replaces the targets.
  func testBatch_WithoutHardLinks() throws {
    try AtomicFile.write([1], to: folder + "/a.png")
    var operations = OutputBatch.FileOperations.system
    operations.link = { _, _ in
      errno = EPERM
      return -1
    }
    let batch = try OutputBatch(
      paths: [folder + "/a.png"], operations: operations)
    try batch.commit([[2]])
    XCTAssertEqual(read(folder + "/a.png"), [2])
    XCTAssertEqual(contents(), ["a.png"])
  }
}
