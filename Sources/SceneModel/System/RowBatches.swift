import Dispatch

/// Rows handed out to worker threads in small batches, the same for both
/// engines.
public enum RowBatches {
  /// Rows per batch: small enough to balance two threads on a 100-row image,
  /// large enough that taking a batch costs nothing next to rendering it.
  public static let rowsPerBatch = 4

  /// Runs `body` over all rows in batches on `threads` workers (the calling
  /// thread among them), reporting finished rows to `progress`.
  public static func forEach(
    rows: Int, threads: Int, progress: (@Sendable (Int) -> Void)?,
    _ body: @Sendable (Range<Int>) -> Void
  ) {
    let batches = (rows + rowsPerBatch - 1) / rowsPerBatch
    let next = AtomicCounter(0)
    let done = AtomicCounter(0)
    let workers = max(1, min(threads, batches))
    withoutActuallyEscaping(body) { body in
      let work: @Sendable () -> Void = {
        while true {
          let batch = next.add(1).old
          guard batch < batches else { return }
          let start = batch * rowsPerBatch
          let end = min(rows, start + rowsPerBatch)
          body(start..<end)
          let finished = done.add(end - start).new
          progress?(finished)
        }
      }
      if workers == 1 {
        work()
      } else {
        DispatchQueue.concurrentPerform(iterations: workers) { _ in work() }
      }
    }
  }
}

extension RowBatches {
  /// The number of processors online, the default thread count.
  public static var availableCores: Int {
    max(1, Int(sysconf(Int32(_SC_NPROCESSORS_ONLN))))
  }
}
