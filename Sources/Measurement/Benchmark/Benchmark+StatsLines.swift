/// What `bench` reads from a child's `--stats` lines on standard error.
extension Benchmark {
  /// The sum of the counts in a `scene: PATH: 6 spheres, 1 planes, 0
  /// triangles, 0 transformed spheres; …` line.
  static func objectCount(inStats text: String) -> Int? {
    guard
      let line = text.split(separator: "\n").first(where: {
        $0.hasPrefix("scene: ")
      }),
      let counts = line.split(separator: ";").first?.split(separator: ":")
        .last
    else { return nil }
    var total = 0
    for part in counts.split(separator: ",") {
      guard let number = part.split(separator: " ").first.flatMap({ Int($0) })
      else { return nil }
      total += number
    }
    return total
  }

  /// The bytes of a `peak memory: 118.1 MiB` line: the child's own peak
  /// (`Memory.ownPeakBytes`), which on Linux `wait4` does not give once
  /// this process has grown, as it has after writing a large scene.
  static func peakBytes(inStats text: String) -> Int? {
    for line in text.split(separator: "\n")
    where line.hasPrefix("peak memory: ") && line.hasSuffix(" MiB") {
      let value = line.dropFirst("peak memory: ".count).dropLast(" MiB".count)
      return Double(value).map { Int(($0 * 1_048_576).rounded()) }
    }
    return nil
  }

  /// The seconds of a `render: 0.1234 s, 45.6 Mrays/s` line.
  static func renderSeconds(inStats text: String) -> Double? {
    for line in text.split(separator: "\n") where line.hasPrefix("render: ") {
      let value = line.dropFirst("render: ".count).prefix { $0 != " " }
      return Double(value)
    }
    return nil
  }
}
