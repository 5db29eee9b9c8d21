import FastEngine
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// The same workload rendered by the peer, Mitsuba 3, through the course
/// tools' `peer_mitsuba.py`, for `raytrace bench --peer`: its warm render
/// beside raytrace's, in one run of the benchmark.
///
/// The peer records depth and normal (its `aov` integrator), one sample at
/// each pixel's centre (`--centre`) or `--spp` jittered samples; raytrace's
/// supersampled rows shade every sample instead (Phong, its lights), which
/// is more work. Each workload is rendered by the peer twice, as it is
/// and with `--freeze` (its kernels recorded and replayed, which helps
/// scenes of many shapes), and the better is kept: the comparison is with
/// the peer at its best.
package struct PeerBenchmark: Sendable {
  /// The path of `peer_mitsuba.py`.
  package var script: String
  /// The peer's timed renders after its first (`--runs`).
  package var runs: Int

  /// Sphere scenes above this count are not given to the peer: its first
  /// render of 10⁵ spheres took 21 s (docs/PERFORMANCE.md).
  package static let sphereLimit = 100_000

  package init(script: String, runs: Int) {
    self.script = script
    self.runs = runs
  }

  /// What the peer reported.
  package struct Result: Sendable, Equatable {
    package var variant: String
    /// Building its scene (reading files, acceleration structure).
    package var loadSeconds: Double
    /// Its first render, kernel compilation included.
    package var firstSeconds: Double
    /// The median of its further renders.
    package var medianSeconds: Double
    package var megaraysPerSecond: Double
    /// Whether this was the `--freeze` run.
    package var frozen = false
  }

  /// Why `script` cannot be run, or nil if it can be read: checked before
  /// the benchmark starts rather than after its first workload.
  package static func problem(withScript script: String) -> String? {
    access(script, R_OK) == 0
      ? nil : "cannot read '\(script)': \(String(cString: strerror(errno)))"
  }

  /// Whether the peer is asked to render `workload` at all.
  package static func accepts(_ workload: Workload) -> Bool {
    if case .randomSpheres(let count) = workload.source {
      return count <= sphereLimit
    }
    return true
  }

  /// The peer's better run of `scene` as `workload` sets it (size,
  /// threads, samples): as it is, and with `--freeze`.
  package func measure(scene: String, _ workload: Workload) throws -> Result {
    let plain = try run(scene: scene, workload, freeze: false)
    var frozen = try run(scene: scene, workload, freeze: true)
    frozen.frozen = true
    return frozen.megaraysPerSecond > plain.megaraysPerSecond ? frozen : plain
  }

  private func run(scene: String, _ workload: Workload, freeze: Bool) throws
    -> Result
  {
    var arguments = [
      "python3", script, scene, "--size", "\(workload.width)",
      "\(workload.height)", "--runs", "\(runs)", "--json",
    ]
    arguments +=
      workload.samples > 1
      ? ["--spp", "\(workload.samples)"] : ["--centre"]
    if let threads = workload.threads {
      arguments += ["--threads", "\(threads)"]
    }
    if freeze { arguments.append("--freeze") }
    // Through env, which finds python3 on the PATH (posix_spawn does not).
    let outcome = try Benchmark.spawn("/usr/bin/env", arguments)
    guard outcome.status == 0, let result = Self.parse(outcome.stderr) else {
      let lines = outcome.stderr.split(separator: "\n")
      throw Benchmark.Failure(
        description: "the peer failed on \(scene): "
          + (lines.last.map(String.init) ?? "exit \(outcome.status)"))
    }
    return result
  }

  /// The numbers of the peer's summary line, which `--json` sends to
  /// standard error: `mitsuba VARIANT WxH: load 1.234 s, first 0.567 s,
  /// median 0.0123 s, 45.6 Mrays/s`. Nil if no line has that form.
  static func parse(_ text: String) -> Result? {
    for line in text.split(separator: "\n") where line.hasPrefix("mitsuba ") {
      let words = line.split(separator: " ")
      func number(after label: String) -> Double? {
        guard let index = words.firstIndex(where: { $0 == label }),
          index + 1 < words.count
        else { return nil }
        return Double(words[index + 1])
      }
      guard words.count >= 2, let load = number(after: "load"),
        let first = number(after: "first"),
        let median = number(after: "median"),
        let rateIndex = words.firstIndex(of: "Mrays/s"), rateIndex > 0,
        let rate = Double(words[rateIndex - 1])
      else { continue }
      return Result(
        variant: String(words[1]), loadSeconds: load, firstSeconds: first,
        medianSeconds: median, megaraysPerSecond: rate)
    }
    return nil
  }
}
