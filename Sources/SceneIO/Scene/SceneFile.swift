import Geometry
import SceneDescription
import PlatformSupport

// Reading scene, mesh and texture files whole: regular files only, up to
// a size limit, with the system's reason on failure.

/// 4 GiB: a scene of tens of millions of spheres, or a mesh of a hundred
/// million triangles.
let maximumFileSize = 1 << 32

struct FileReadError: Error {
  var reason: String
}

/// The whole file in one read; errors carry the system's reason.
///
/// Only regular files up to `maximumFileSize` are read: a device such as
/// /dev/zero, a FIFO or a directory named as a scene or a mesh would
/// otherwise hang the program or exhaust its memory.
func readFile(_ path: String) throws(FileReadError) -> [UInt8] {
  let (descriptor, size) = try openRegularFile(path)
  return try readOpenFile(descriptor, expected: size)
}

/// Opens `path` for reading if it is a regular file of at most
/// `maximumFileSize` bytes: its descriptor, and its size as reported.
func openRegularFile(
  _ path: String
) throws(FileReadError) -> (descriptor: Int32, size: Int) {
  // Non-blocking: opening a FIFO for reading would otherwise wait for a
  // writer, forever, before fstat below could refuse it. The flag changes
  // nothing for the regular files that are read.
  let descriptor = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC)
  guard descriptor >= 0 else {
    throw FileReadError(
      reason: "cannot open the file: \(String(cString: strerror(errno)))")
  }
  var status = stat()
  guard fstat(descriptor, &status) == 0 else {
    let reason = String(cString: strerror(errno))
    close(descriptor)
    throw FileReadError(reason: "cannot read the file: \(reason)")
  }
  guard (status.st_mode & S_IFMT) == S_IFREG else {
    close(descriptor)
    throw FileReadError(reason: "not a regular file")
  }
  guard Int(status.st_size) <= maximumFileSize else {
    close(descriptor)
    throw FileReadError(
      reason:
        "the file is \(status.st_size) bytes; the limit is \(maximumFileSize)")
  }
  return (descriptor, Int(status.st_size))
}

/// Reads the file open at `descriptor` to its end, and closes it.
func readOpenFile(
  _ descriptor: Int32, expected: Int
) throws(FileReadError) -> [UInt8] {
  guard let handle = fdopen(descriptor, "rb") else {
    let reason = String(cString: strerror(errno))
    close(descriptor)
    throw FileReadError(reason: "cannot open the file: \(reason)")
  }
  defer { fclose(handle) }
  // Straight into the array when the size is right: a 72 MB scene was
  // otherwise copied once more, chunk by chunk. A file that grows while it
  // is read goes on in chunks.
  var failed = false
  var bytes = [UInt8](unsafeUninitializedCapacity: expected) { buffer, count in
    count = fread(buffer.baseAddress, 1, expected, handle)
    failed = count < expected && ferror(handle) != 0
  }
  var chunk = [UInt8](
    repeating: 0, count: failed || bytes.count < expected ? 0 : 1 << 16)
  while !failed && !chunk.isEmpty {
    let read = chunk.withUnsafeMutableBytes {
      fread($0.baseAddress, 1, $0.count, handle)
    }
    if read > 0 { bytes.append(contentsOf: chunk[0..<read]) }
    if read < chunk.count {
      failed = ferror(handle) != 0
      break
    }
  }
  if failed {
    throw FileReadError(
      reason: "cannot read the file: \(String(cString: strerror(errno)))")
  }
  return bytes
}
