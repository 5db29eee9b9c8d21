import ArgumentParser
import FastEngine
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// `raytrace bench`: the fixed workloads of the README's performance table.
struct Bench: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "bench",
    abstract:
      "Time the fast engine on fixed workloads and print a Markdown table.",
    discussion: """
      Every workload is rendered by the fast engine (--engine fast), the \
      engine the timings are about. \
      Each workload runs as its own raytrace process: one warm-up, then \
      --runs timed runs, then one run that renders twice --runs more times \
      (--repeat). 'render, warm' is the median of those repeated renders \
      (rendering only, as peers that time repeated renders in one process \
      report it) and Mrays/s its throughput, every sample counted; \
      'render, first' the median of \
      the timed runs' only render, cold caches and fresh buffers included; \
      'end to end' the median wall time of the timed runs (parse, build, \
      render, write PNGs); 'peak memory' their largest resident set. The \
      random sphere and mesh scenes are written to --data on first use; the \
      MIT assignment's bunny and arch are read from --reference (the \
      assignment's scene folder, with its models/), and left out without \
      it; run from the project's root. With --peer, \
      each workload is also rendered by Mitsuba 3 through the course tools' \
      peer_mitsuba.py (as it is and with --freeze, the better kept; depth \
      and normals at pixel centres, or --spp jittered samples), and its warm \
      Mrays/s and raytrace's ratio to it are added to the row. 'samples' \
      reads '16, all' where depth and normals are the means of 16 samples \
      (--sample-all-outputs): the peer's work at --spp 16.
      """)

  @Option(help: "Timed runs per workload, after one warm-up.")
  var runs: Int = 5

  @Option(
    help: ArgumentHelp(
      "Folder for generated scenes and images.", valueName: "dir"))
  var data: String = ".build/bench"

  @Option(
    help: ArgumentHelp(
      "Folder of the MIT assignment's scenes (bunny, arch).",
      valueName: "dir"))
  var reference: String?

  @Option(
    help: ArgumentHelp(
      "Also time Mitsuba 3 on each workload with this peer_mitsuba.py.",
      valueName: "script"))
  var peer: String?

  @Flag(
    help:
      "Skip the workloads of 10⁶ objects or more and of 3840x2160."
  )
  var quick = false

  mutating func validate() throws {
    guard !Raytrace.defersValidation else { return }
    guard runs >= 1 else { throw ValidationError("--runs must be at least 1.") }
    if let peer, let problem = PeerBenchmark.problem(withScript: peer) {
      throw ValidationError("--peer: \(problem).")
    }
  }

  func run() throws {
    let benchmark = Benchmark(
      executable: currentExecutable(), dataFolder: data, runs: runs,
      referenceFolder: reference)
    let peerBenchmark = peer.map { PeerBenchmark(script: $0, runs: runs) }
    let peerHeader =
      peerBenchmark == nil ? "" : " Mitsuba 3 (Mrays/s) | ÷ Mitsuba |"
    printOutput(
      "| workload | size | objects | threads | outputs | samples | "
        + "render, warm (ms) | Mrays/s | render, first (ms) | end to end (s) | "
        + "peak memory (MiB) |" + peerHeader
    )
    printOutput(
      "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|"
        + (peerBenchmark == nil ? "" : "---:|---:|"))
    var endToEnd: [Int: Double] = [:]
    var missing: Set<String> = []
    for workload in Workload.standard {
      if quick
        && (workload.width * workload.height > 1920 * 1080
          || (workload.generatedCount ?? 0) >= 1_000_000)
      {
        continue
      }
      guard benchmark.isAvailable(workload) else {
        missing.insert(workload.name)
        continue
      }
      do {
        let result = try benchmark.measure(workload)
        var peerColumns = ""
        if let peerBenchmark {
          if PeerBenchmark.accepts(workload) {
            let peer = try peerBenchmark.measure(
              scene: result.scenePath, workload)
            let ratio = result.megaraysPerSecond / peer.megaraysPerSecond
            peerColumns =
              " \(formatted(peer.megaraysPerSecond, digits: 3)) | "
              + "\(formatted(ratio, digits: 3))× |"
          } else {
            peerColumns = " – | – |"
          }
        }
        let objects =
          workload.generatedCount.map(String.init)
          ?? result.objects.map(String.init) ?? "?"
        printOutput(
          "| \(workload.name) | \(workload.width)×\(workload.height) | "
            + "\(objects) | "
            + "\(result.threads) | "
            + "\(workload.outputs.names.joined(separator: " + ")) | "
            + "\(workload.samples)"
            + (workload.samplesAllOutputs ? ", all | " : " | ")
            + "\(formatted(result.warmRenderSeconds * 1000, digits: 3)) | "
            + "\(formatted(result.megaraysPerSecond, digits: 3)) | "
            + "\(formatted(result.renderSeconds * 1000, digits: 3)) | "
            + "\(formatted(result.endToEndSeconds, digits: 3)) | "
            + "\(formatted(Double(result.peakBytes) / 1_048_576, digits: 3)) |"
            + peerColumns)
        if case .randomSpheres(let count) = workload.source,
          workload.threads == nil,
          workload.outputs == [.depth, .normals]
        {
          endToEnd[count] = result.endToEndSeconds
        }
      } catch {
        printError("raytrace: error: \(error)")
        throw ExitCode.failure
      }
    }
    if !missing.isEmpty {
      printOutput(
        "\nLeft out ("
          + (reference.map { "not in \($0)" } ?? "no --reference folder")
          + "): "
          + missing.sorted().joined(separator: ", "))
    }
    // The issue's scaling goal, read off the rows above.
    if let large = endToEnd[1_000_000], let small = endToEnd[10_000] {
      printOutput(
        "\n10⁶ spheres end to end ÷ 10⁴ spheres end to end (depth + normals, "
          + "all cores): "
          + "\(formatted(large / small, digits: 3))×")
    }
  }

  /// This very executable, so that the benchmark times the build it ships in.
  private func currentExecutable() -> String {
    Platform.currentExecutable() ?? CommandLine.arguments[0]
  }
}
