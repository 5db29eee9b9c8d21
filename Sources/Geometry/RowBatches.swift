import Dispatch
import Foundation

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
    let counts = Counts()
    let workers = max(1, min(threads, batches))
    withoutActuallyEscaping(body) { body in
      let work: @Sendable () -> Void = {
        while true {
          let batch = counts.take()
          guard batch < batches else { return }
          let start = batch * rowsPerBatch
          let end = min(rows, start + rowsPerBatch)
          body(start..<end)
          let finished = counts.finish(end - start)
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

  /// The next batch to take and the rows finished, behind a lock taken
  /// once per batch (`Synchronization.Atomic` would need macOS 15).
  private final class Counts: @unchecked Sendable {
    private let lock = NSLock()
    private var next = 0
    private var done = 0

    /// The next batch's index.
    func take() -> Int {
      lock.lock()
      defer { lock.unlock() }
      next += 1
      return next - 1
    }

    /// Adds `rows` finished; the rows finished so far.
    func finish(_ rows: Int) -> Int {
      lock.lock()
      defer { lock.unlock() }
      done += rows
      return done
    }
  }
}
