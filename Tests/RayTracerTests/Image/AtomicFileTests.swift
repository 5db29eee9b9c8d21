import XCTest

@testable import RayTracer

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

  func contents() -> [String] {
    guard let directory = opendir(folder) else { return [] }
    defer { closedir(directory) }
    var names: [String] = []
    while let entry = readdir(directory) {
      let name = withUnsafeBytes(of: entry.pointee.d_name) { raw in
        String(decoding: raw.prefix { $0 != 0 }, as: UTF8.self)
      }
      if name != "." && name != ".." { names.append(name) }
    }
    return names.sorted()
  }

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
    XCTAssertEqual(read(folder + "/keep.bin"), [1], "the first file must not be replaced")
    XCTAssertEqual(contents(), ["keep.bin"], "no temporary may be left behind")
  }

  func testCheckWritable_AcceptsANewFileAndLeavesNothing() throws {
    try AtomicFile.checkWritable(folder + "/new.png")
    XCTAssertEqual(contents(), [])
  }

  func testCheckWritable_RefusesAMissingFolderADirectoryAndAReadOnlyFolder() throws {
    XCTAssertThrowsError(try AtomicFile.checkWritable(folder + "/no/such/dir.png")) {
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

  func testTemporaryPath_StaysInTheTargetsFolder() {
    let pid = getpid()
    XCTAssertEqual(AtomicFile.temporaryPath(for: "a/b/c.png"), "a/b/.c.png.raytrace-\(pid).tmp")
    XCTAssertEqual(AtomicFile.temporaryPath(for: "c.png"), ".c.png.raytrace-\(pid).tmp")
  }
}
