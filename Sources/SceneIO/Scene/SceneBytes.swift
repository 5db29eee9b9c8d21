import Geometry
import SceneDescription
import PlatformSupport

/// The bytes a scene is parsed from, immutable once read, so the threads
/// of a parse share them.
///
/// A large file is read in parts at once, one per thread, with `pread`,
/// into memory advised onto 2 MiB pages: the copy out of the page cache
/// and the zeroing of fresh pages had been a fifth of a large scene's
/// parse, all of it before any thread of the parse could start.
/// Mapping the file instead measured a little faster, but a mapped file
/// that another process truncates raises SIGBUS mid-parse: a crash where
/// a read gives a consistent copy, or an error.
final class SceneBytes: @unchecked Sendable {
  let buffer: UnsafeBufferPointer<UInt8>

  /// Smaller files are read in one piece: splitting costs a thread's
  /// wake-up, which the copy of a small file does not repay. Larger ones
  /// are read in parts of at least half this, one per thread.
  static let splitThreshold = 1 << 20

  init(_ bytes: [UInt8]) {
    let copy = UnsafeMutableBufferPointer<UInt8>.allocate(capacity: bytes.count)
    _ = copy.initialize(from: bytes)
    buffer = UnsafeBufferPointer(copy)
  }

  private init(filled: UnsafeMutableBufferPointer<UInt8>) {
    buffer = UnsafeBufferPointer(filled)
  }

  deinit {
    buffer.deallocate()
  }

  /// The file at `path`, read by up to `threads` threads; errors, and the
  /// files refused, are `readFile`'s.
  static func contentsOf(_ path: String, threads: Int = 2)
    throws(FileReadError) -> SceneBytes
  {
    let (descriptor, size) = try openRegularFile(path)
    let parts = Parallel.parts(
      size, threads: threads, from: splitThreshold,
      minimum: splitThreshold / 2)
    if parts > 1, let bytes = readInParts(descriptor, size: size, parts) {
      close(descriptor)
      return bytes
    }
    return SceneBytes(try readOpenFile(descriptor, expected: size))
  }

  /// Exactly `size` bytes read by `parts` threads, or nil when the file
  /// did not have exactly that many (it changed since its size was taken)
  /// or a read failed: the caller then reads it the ordinary way, which
  /// reports the error or follows the file's new length.
  private static func readInParts(
    _ descriptor: Int32, size: Int, _ parts: Int
  ) -> SceneBytes? {
    let buffer = UnsafeMutableBufferPointer<UInt8>.allocate(capacity: size)
    Memory.adviseHugePages(UnsafeMutableRawBufferPointer(buffer))
    let complete = UnsafeMutableBufferPointer<Bool>.allocate(capacity: parts)
    defer { complete.deallocate() }
    let shared = Shared((buffer, complete))
    Parallel.inParts(size, parts) { part, range in
      let (buffer, complete) = shared.value
      var offset = range.lowerBound
      while offset < range.upperBound {
        let count = pread(
          descriptor, buffer.baseAddress! + offset, range.upperBound - offset,
          off_t(offset))
        if count < 0 && errno == EINTR { continue }
        guard count > 0 else { break }
        offset += count
      }
      complete[part] = offset == range.upperBound
    }
    var probe: UInt8 = 0
    guard complete.allSatisfy({ $0 }),
      pread(descriptor, &probe, 1, off_t(size)) == 0
    else {
      buffer.deallocate()
      return nil
    }
    return SceneBytes(filled: buffer)
  }
}
