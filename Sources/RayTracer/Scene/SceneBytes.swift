#if canImport(Glibc)
import Glibc
#elseif canImport(Darwin)
import Darwin
#endif

/// The bytes a scene is parsed from: a large file mapped into memory, or a
/// copy of an array. Immutable once made, so the threads of a parse share
/// it.
///
/// Mapping a large scene skips the copy from the page cache into fresh
/// memory, and the zeroing of that memory: about 35 ms of the 0.19 s a
/// 72 MB scene took to parse, all of it before either thread could start.
///
/// A mapped file that another process truncates while it is parsed
/// raises SIGBUS at the first page past its new end; a file that grows is
/// parsed as it was when mapped. Reading it would give a consistent copy,
/// but the risk is that of any program that maps its input, and only
/// files of at least `mappingThreshold` bytes take it.
final class SceneBytes: @unchecked Sendable {
  let buffer: UnsafeBufferPointer<UInt8>
  let isMapped: Bool

  /// Smaller files are read: the copy costs little there, and files
  /// whose reported size is not their length (as under /proc) are small.
  static let mappingThreshold = 1 << 20

  init(_ bytes: [UInt8]) {
    let copy = UnsafeMutableBufferPointer<UInt8>.allocate(capacity: bytes.count)
    _ = copy.initialize(from: bytes)
    buffer = UnsafeBufferPointer(copy)
    isMapped = false
  }

  private init(mapped start: UnsafeRawPointer, count: Int) {
    buffer = UnsafeBufferPointer(
      start: start.assumingMemoryBound(to: UInt8.self), count: count)
    isMapped = true
  }

  deinit {
    if isMapped {
      munmap(
        UnsafeMutableRawPointer(mutating: buffer.baseAddress), buffer.count)
    } else {
      buffer.deallocate()
    }
  }

  /// The file at `path`, mapped when it is large and the system allows,
  /// read otherwise; errors, and the files refused, are `readFile`'s.
  static func contentsOf(_ path: String) throws(FileReadError) -> SceneBytes {
    let (descriptor, size) = try openRegularFile(path)
    if size >= mappingThreshold {
      // Not populated up front: each thread of the parse then takes the
      // page faults of its own half, which measured as fast as mapping
      // every page before either starts.
      let start = mmap(nil, size, PROT_READ, MAP_PRIVATE, descriptor, 0)
      if let start, start != MAP_FAILED {
        close(descriptor)
        return SceneBytes(mapped: start, count: size)
      }
    }
    return SceneBytes(try readOpenFile(descriptor, expected: size))
  }
}
