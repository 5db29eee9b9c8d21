import PlatformSupport

/// The line that names the fast engine while the default engine is still
/// rendering a scene it will take long over: once the rows finished, at
/// their pace, put the whole render past `limit` seconds (and half a
/// second has passed), one line on standard error saying how far it got
/// in how long, so that a user waiting on 10⁵ spheres learns why before
/// the end. Scripts get it too: it is one line.
final class SlowRenderNote: Sendable {
  private let total: Int
  private let limit: Double
  private let start = Stopwatch.now()
  private let printed = AtomicCounter(0)

  init(rows: Int, limit: Double) {
    total = rows
    self.limit = limit
  }

  /// Called by the workers with the rows finished so far; `clear` runs
  /// just before the line is printed (the progress bar's line is cleared).
  func update(_ finished: Int, clear: () -> Void) {
    guard finished > 0, finished < total, printed.load() == 0 else { return }
    let elapsed = Stopwatch.now() - start
    let estimate = elapsed * Double(total) / Double(finished)
    guard elapsed >= 0.5, estimate > limit,
      printed.exchange(expected: 0, desired: 1)
    else { return }
    // What was measured, not a forecast: rows differ (the sky is quick).
    let percent = max(1, finished * 100 / total)
    let seconds = Double((elapsed * 10).rounded()) / 10
    clear()
    printError(
      "raytrace: note: the course engine tests every object for every ray: "
        + "\(percent)% of the rows in \(seconds) s (--engine fast renders "
        + "the same scene in a fraction of that)")
  }
}
