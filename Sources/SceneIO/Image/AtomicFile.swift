import SceneModel

/// Why an output file could not be written; the description is one sentence
/// naming the path and the system's reason.
public struct OutputError: Error, CustomStringConvertible, Sendable {
  public var path: String
  public var reason: String
  public var description: String {
    "cannot write '\(SceneParser.escaped(path))': \(reason)"
  }
}

/// Writes files whole or not at all (see `OutputBatch`): a failed or
/// interrupted run never leaves a partial image and never truncates an
/// existing one.
public enum AtomicFile {
  /// Checks, before any rendering, that `path` can be created or replaced:
  /// creates and removes a temporary file in its folder, which is the very
  /// operation the final write needs.
  public static func checkWritable(_ path: String) throws(OutputError) {
    let batch = try OutputBatch(paths: [path])
    batch.abandon()
  }

  /// Writes `bytes` to `path` atomically.
  public static func write(
    _ bytes: [UInt8], to path: String
  ) throws(OutputError) {
    try writeAll([(bytes, path)])
  }

  /// Writes every file, all or none (`OutputBatch`).
  public static func writeAll(
    _ files: [(bytes: [UInt8], path: String)]
  ) throws(OutputError) {
    let batch = try OutputBatch(paths: files.map(\.path))
    try batch.commit(files.map(\.bytes))
  }

  /// Installs, once, the handlers that undo the outputs in flight when a
  /// terminating signal arrives (see `PendingFiles.installHandlers`).
  public static func installInterruptCleanup() {
    PendingFiles.installHandlers()
  }
}
