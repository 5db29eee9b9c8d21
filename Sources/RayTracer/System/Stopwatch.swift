/// Wall-clock intervals from a monotonic clock.
public struct Stopwatch {
  private var last = Stopwatch.now()

  public init() {}

  /// Seconds since the previous lap (or since creation), and starts a new one.
  public mutating func lap() -> Double {
    let now = Stopwatch.now()
    defer { last = now }
    return now - last
  }

  /// Seconds on the monotonic clock since an arbitrary start.
  public static func now() -> Double {
    var time = timespec()
    clock_gettime(CLOCK_MONOTONIC, &time)
    return Double(time.tv_sec) + Double(time.tv_nsec) * 1e-9
  }
}
