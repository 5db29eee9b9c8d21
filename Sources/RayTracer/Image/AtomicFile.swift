/// Why an output file could not be written; the description is one sentence
/// naming the path and the system's reason.
public struct OutputError: Error, CustomStringConvertible, Sendable {
  public var path: String
  public var reason: String
  public var description: String { "cannot write '\(path)': \(reason)" }
}

/// Writes files whole or not at all: each goes to a temporary file beside its
/// target and is renamed over it only when every file of the batch is
/// complete, so a failed or interrupted run never leaves a partial image and
/// never truncates an existing one.
///
/// While temporary files exist, SIGINT, SIGTERM and SIGHUP remove them before
/// the process ends (`installInterruptCleanup()`).
public enum AtomicFile {
  /// Checks, before any rendering, that `path` can be created or replaced:
  /// creates and removes a temporary file in its folder, which is the very
  /// operation the final write needs.
  public static func checkWritable(_ path: String) throws(OutputError) {
    var status = stat()
    if stat(path, &status) == 0 && (status.st_mode & S_IFMT) == S_IFDIR {
      throw OutputError(path: path, reason: "it is a directory")
    }
    let temporary = temporaryPath(for: path)
    let descriptor = open(temporary, O_WRONLY | O_CREAT | O_EXCL, 0o644)
    guard descriptor >= 0 else {
      throw OutputError(path: path, reason: systemReason())
    }
    close(descriptor)
    unlink(temporary)
  }

  /// Writes `bytes` to `path` atomically.
  public static func write(_ bytes: [UInt8], to path: String) throws(OutputError) {
    try writeAll([(bytes, path)])
  }

  /// Writes every file to its temporary, then renames them all; on any
  /// failure every temporary is removed and no target is touched.
  public static func writeAll(_ files: [(bytes: [UInt8], path: String)]) throws(OutputError) {
    installInterruptCleanup()
    var temporaries: [String] = []
    defer {
      for temporary in temporaries {
        unlink(temporary)
        PendingFiles.remove(temporary)
      }
    }
    for (bytes, path) in files {
      let temporary = temporaryPath(for: path)
      guard PendingFiles.add(temporary) else {
        throw OutputError(path: path, reason: "too many outputs at once")
      }
      temporaries.append(temporary)
      try writeWhole(bytes, to: temporary, reportingAs: path)
    }
    for (index, file) in files.enumerated() {
      guard rename(temporaries[index], file.path) == 0 else {
        throw OutputError(path: file.path, reason: systemReason())
      }
    }
  }

  private static func writeWhole(
    _ bytes: [UInt8], to temporary: String, reportingAs path: String
  ) throws(OutputError) {
    let descriptor = open(temporary, O_WRONLY | O_CREAT | O_EXCL, 0o644)
    guard descriptor >= 0 else { throw OutputError(path: path, reason: systemReason()) }
    defer { close(descriptor) }
    var written = 0
    while written < bytes.count {
      let result = bytes.withUnsafeBytes { buffer in
        Platform.writeBytes(
          descriptor, buffer.baseAddress! + written, buffer.count - written)
      }
      if result < 0 {
        if errno == EINTR { continue }
        throw OutputError(path: path, reason: systemReason())
      }
      written += result
    }
  }

  /// `.NAME.raytrace-PID.tmp` in the target's folder, so that the rename
  /// stays within one file system.
  static func temporaryPath(for path: String) -> String {
    let slash = path.lastIndex(of: "/")
    let folder = slash.map { String(path[...$0]) } ?? ""
    let name = slash.map { String(path[path.index(after: $0)...]) } ?? path
    return "\(folder).\(name).raytrace-\(getpid()).tmp"
  }

  private static func systemReason() -> String {
    String(cString: strerror(errno))
  }

  /// Installs, once, handlers for SIGINT, SIGTERM and SIGHUP that remove the
  /// pending temporary files and then end the process as the signal would.
  public static func installInterruptCleanup() {
    PendingFiles.installHandlers()
  }
}

/// The temporary files in flight, in fixed C storage that a signal handler
/// can read without allocating or locking.
enum PendingFiles {
  static let slots = 8
  static let slotSize = 4096
  nonisolated(unsafe) static let storage: UnsafeMutablePointer<CChar> = {
    let pointer = UnsafeMutablePointer<CChar>.allocate(capacity: slots * slotSize)
    pointer.initialize(repeating: 0, count: slots * slotSize)
    return pointer
  }()
  nonisolated(unsafe) static var installed = false

  /// False when every slot is taken or the path is too long to store.
  static func add(_ path: String) -> Bool {
    let utf8 = Array(path.utf8CString)
    guard utf8.count <= slotSize else { return false }
    for slot in 0..<slots where storage[slot * slotSize] == 0 {
      for (index, byte) in utf8.enumerated().reversed() {
        // Written last to first, so the slot reads as empty until the
        // path is complete.
        storage[slot * slotSize + index] = byte
      }
      return true
    }
    return false
  }

  static func remove(_ path: String) {
    for slot in 0..<slots where storage[slot * slotSize] != 0 {
      if String(cString: storage + slot * slotSize) == path {
        storage[slot * slotSize] = 0
      }
    }
  }

  static func installHandlers() {
    guard !installed else { return }
    installed = true
    for signalNumber in [SIGINT, SIGTERM, SIGHUP] {
      signal(signalNumber) { received in
        for slot in 0..<PendingFiles.slots
        where PendingFiles.storage[slot * PendingFiles.slotSize] != 0 {
          unlink(PendingFiles.storage + slot * PendingFiles.slotSize)
        }
        signal(received, SIG_DFL)
        raise(received)
      }
    }
  }
}
