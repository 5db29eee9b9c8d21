import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// A progress bar on standard error for renders that take more than about
/// a second, and only when standard error is a terminal: scripts and
/// redirected logs get nothing.
final class ProgressBar: Sendable {
  let total: Int
  private let start = Stopwatch.now()
  /// The last permille drawn, so that concurrent workers draw each step once.
  private let drawn = AtomicCounter(-1)
  /// 1 once the bar has been drawn.
  private let visible = AtomicCounter(0)

  /// Nil when standard error is not a terminal.
  init?(rows: Int) {
    guard isatty(2) == 1, rows > 0 else { return nil }
    total = rows
  }

  /// Called by the workers with the number of rows finished so far.
  func update(_ finished: Int) {
    let elapsed = Stopwatch.now() - start
    // Estimate the whole render from its progress; stay silent when it
    // will be done within a second.
    guard elapsed > 0.25, elapsed * Double(total) / Double(max(finished, 1)) > 1
    else { return }
    let permille = finished * 1000 / total
    let previous = drawn.load()
    guard
      permille / 10 > previous / 10 || (permille == 1000 && previous != 1000)
    else { return }
    guard drawn.exchange(expected: previous, desired: permille)
    else { return }
    visible.store(1)
    let width = 40
    let filled = permille * width / 1000
    let bar =
      String(repeating: "#", count: filled)
      + String(repeating: ".", count: width - filled)
    printRaw("\rrendering [\(bar)] \(permille / 10)%")
  }

  /// Clears the bar's line, if one was drawn.
  func finish() {
    if visible.load() == 1 {
      printRaw("\r\u{1B}[K")
    }
  }

  private func printRaw(_ text: String) {
    let bytes = Array(text.utf8)
    _ = bytes.withUnsafeBytes { write(2, $0.baseAddress, $0.count) }
  }
}
