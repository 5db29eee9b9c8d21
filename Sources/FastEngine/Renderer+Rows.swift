import Geometry

/// The fast engine's rows, handed out in batches to the render's threads
/// (`RowBatches`).
extension Renderer {
  static var rowsPerBatch: Int { RowBatches.rowsPerBatch }

  static func forEachRowBatch(
    rows: Int, threads: Int, progress: (@Sendable (Int) -> Void)?,
    _ body: @Sendable (Range<Int>) -> Void
  ) {
    RowBatches.forEach(
      rows: rows, threads: threads, progress: progress, body)
  }
}
