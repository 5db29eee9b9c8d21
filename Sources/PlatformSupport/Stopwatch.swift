/// Wall-clock intervals from a monotonic clock.
package struct Stopwatch {
  private var last = Stopwatch.now()

  package init() {}

  /// Seconds since the previous lap (or since creation), and starts a new one.
  package mutating func lap() -> Double {
    let now = Stopwatch.now()
    defer { last = now }
    return now - last
  }

  /// Seconds on the monotonic clock since an arbitrary start.
  package static func now() -> Double {
    var time = timespec()
    clock_gettime(CLOCK_MONOTONIC, &time)
    return Double(time.tv_sec) + Double(time.tv_nsec) * 1e-9
  }
}

/// The middle value (the mean of the two middle ones for an even count).
package func median(_ values: [Double]) -> Double {
  guard !values.isEmpty else { return .nan }
  let sorted = values.sorted()
  let middle = sorted.count / 2
  return sorted.count % 2 == 1
    ? sorted[middle] : (sorted[middle - 1] + sorted[middle]) / 2
}
