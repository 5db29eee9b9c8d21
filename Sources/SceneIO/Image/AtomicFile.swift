import Geometry

/// Why an output file could not be written; the description is one sentence
/// naming the path and the system's reason.
package struct OutputError: Error, CustomStringConvertible, Sendable {
  package var path: String
  package var reason: String
  package var description: String {
    "cannot write '\(SceneParser.escaped(path))': \(reason)"
  }
}

/// Writes files whole or not at all (see `OutputBatch`): a failed or
/// interrupted run never leaves a partial image and never truncates an
/// existing one.
package enum AtomicFile {
  /// Checks, before any rendering, that `path` can be created or replaced:
  /// creates and removes a temporary file in its folder, which is the very
  /// operation the final write needs.
  package static func checkWritable(_ path: String) throws(OutputError) {
    let batch = try OutputBatch(paths: [path])
    batch.abandon()
  }

  /// Writes `bytes` to `path` atomically.
  package static func write(
    _ bytes: [UInt8], to path: String
  ) throws(OutputError) {
    try writeAll([(bytes, path)])
  }

  /// Writes every file, all or none (`OutputBatch`).
  package static func writeAll(
    _ files: [(bytes: [UInt8], path: String)]
  ) throws(OutputError) {
    let batch = try OutputBatch(paths: files.map(\.path))
    try batch.commit(files.map(\.bytes))
  }

  /// Installs, once, the handlers that undo the outputs in flight when a
  /// terminating signal arrives (see `PendingFiles.installHandlers`).
  package static func installInterruptCleanup() {
    PendingFiles.installHandlers()
  }
}
