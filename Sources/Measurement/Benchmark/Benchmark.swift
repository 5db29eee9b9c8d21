import FastEngine
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// One fixed workload of `raytrace bench`.
package struct Workload: Sendable {
  package enum Source: Sendable {
    /// A scene file of the project, relative to its root.
    case file(String)
    /// `RandomSpheres` with this many spheres, written once to the data
    /// folder.
    case randomSpheres(Int)
    /// `RandomMesh` with this many triangles, written once to the data
    /// folder.
    case randomMesh(Int)
    /// A scene of the MIT assignment, by its file name in the reference
    /// folder (`Benchmark.referenceFolder`); skipped where that is absent.
    case reference(String)
  }

  package var name: String
  package var source: Source
  package var width: Int
  package var height: Int
  /// Nil: all cores.
  package var threads: Int?
  package var outputs: RenderOutputs
  /// Rays per pixel of the shaded image (`--samples`).
  package var samples = 1
  /// Depth and normals the means of the samples too
  /// (`--sample-all-outputs`): the work of a peer's supersampled AOVs.
  package var samplesAllOutputs = false

  /// The workloads of the README's table: the course-like scene at two
  /// sizes, random spheres from 100 to 10⁶, what leaving outputs out saves,
  /// one thread against all, 16 samples a pixel, and meshes and the MIT
  /// scenes like for like with the peer (`likeForLike`).
  package static let standard: [Workload] = {
    let course = Source.file("scenes/spheres.txt")
    let spheres = "random spheres"
    let aov: RenderOutputs = [.depth, .normals]
    let all: RenderOutputs = [.depth, .normals, .shaded]
    func row(
      _ name: String, _ source: Source, _ width: Int, _ height: Int,
      _ outputs: RenderOutputs, threads: Int? = nil, samples: Int = 1,
      samplesAllOutputs: Bool = false
    ) -> Workload {
      Workload(
        name: name, source: source, width: width, height: height,
        threads: threads, outputs: outputs, samples: samples,
        samplesAllOutputs: samplesAllOutputs)
    }
    /// One sample of depth and normals, 16 of the shaded image, and 16 of
    /// depth and normals: a peer's AOVs, its shading, its supersampled AOVs.
    func likeForLike(
      _ name: String, _ source: Source, _ width: Int, _ height: Int
    ) -> [Workload] {
      [
        row(name, source, width, height, aov),
        row(name, source, width, height, [.shaded], samples: 16),
        row(
          name, source, width, height, aov, samples: 16,
          samplesAllOutputs: true),
      ]
    }
    let first = [
      row("course scene", course, 800, 800, aov),
      row("course scene", course, 800, 800, all),
      row("course scene", course, 800, 800, all, threads: 1),
      row("course scene", course, 3840, 2160, all),
      row(spheres, .randomSpheres(100), 1920, 1080, aov),
      row(spheres, .randomSpheres(10_000), 1920, 1080, [.depth]),
      row(spheres, .randomSpheres(10_000), 1920, 1080, aov),
      row(spheres, .randomSpheres(10_000), 1920, 1080, all),
      row(spheres, .randomSpheres(10_000), 1920, 1080, aov, threads: 1),
      row(spheres, .randomSpheres(1_000_000), 1920, 1080, aov),
      row("course scene", course, 800, 800, [.shaded], samples: 16),
      row(spheres, .randomSpheres(10_000), 1920, 1080, [.shaded], samples: 16),
    ]
    let meshes = [1_000, 100_000, 1_000_000].flatMap {
      likeForLike("mesh", .randomMesh($0), 1920, 1080)
    }
    return first + meshes
      + [row("mesh", .randomMesh(5_000_000), 1920, 1080, aov)]
      + likeForLike("bunny_1k", .reference("scene06_bunny_1k.txt"), 800, 800)
      + likeForLike("arch", .reference("scene07_arch.txt"), 800, 800)
  }()

  package init(
    name: String, source: Source, width: Int, height: Int, threads: Int? = nil,
    outputs: RenderOutputs, samples: Int = 1, samplesAllOutputs: Bool = false
  ) {
    self.name = name
    self.source = source
    self.width = width
    self.height = height
    self.threads = threads
    self.outputs = outputs
    self.samples = samples
    self.samplesAllOutputs = samplesAllOutputs
  }

  /// The generated scenes' object count; nil for a scene file, whose
  /// count the run reports (`BenchmarkResult.objects`).
  package var generatedCount: Int? {
    switch source {
    case .file, .reference: nil
    case .randomSpheres(let count), .randomMesh(let count): count
    }
  }
}

/// One measured row.
package struct BenchmarkResult: Sendable {
  package var workload: Workload
  package var scenePath: String
  package var threads: Int
  /// Median render time (the `render:` line of `--stats`) over the runs,
  /// each the first and only render of its process.
  package var renderSeconds: Double
  /// The median of 2 × `runs` renders repeated in one process after its
  /// first (`--repeat`): a warm render, as peers that time repeated renders
  /// in one process report it.
  package var warmRenderSeconds: Double
  /// Median wall time of the whole process: parse, build, render, write.
  package var endToEndSeconds: Double
  /// The largest resident set of any run, in bytes.
  package var peakBytes: Int
  /// Spheres, planes, triangles and transformed spheres, as the render
  /// reported them (`--stats`).
  package var objects: Int?

  /// Camera rays per second of the warm render, every sample counted.
  package var megaraysPerSecond: Double {
    Double(workload.width * workload.height * workload.samples)
      / warmRenderSeconds / 1e6
  }
}

/// Runs workloads as separate processes of the `raytrace` executable, so
/// that each one's peak memory is its own (as it reports it with `--stats`;
/// `wait4`'s resource usage where it does not) and the
/// end-to-end time is what a user waits for.
package struct Benchmark {
  package var executable: String
  package var dataFolder: String
  package var runs: Int
  /// The MIT assignment's scenes, for the bunny and arch workloads; nil
  /// leaves them out.
  package var referenceFolder: String?

  package init(
    executable: String, dataFolder: String, runs: Int,
    referenceFolder: String? = nil
  ) {
    self.executable = executable
    self.dataFolder = dataFolder
    self.runs = runs
    self.referenceFolder = referenceFolder
  }

  /// Whether `workload`'s scene can be had: a reference scene only where
  /// the reference folder holds it.
  package func isAvailable(_ workload: Workload) -> Bool {
    guard case .reference(let name) = workload.source else { return true }
    guard let referenceFolder else { return false }
    return access("\(referenceFolder)/\(name)", R_OK) == 0
  }

  package struct Failure: Error, CustomStringConvertible {
    package var description: String
  }

  /// The scene file for `workload`, writing a random scene on first use.
  package func scenePath(for workload: Workload) throws -> String {
    switch workload.source {
    case .file(let path):
      return path
    case .reference(let name):
      return "\(referenceFolder ?? ".")/\(name)"
    case .randomSpheres(let count):
      let path = "\(dataFolder)/random-\(count).txt"
      if access(path, R_OK) != 0 {
        mkdir(dataFolder, 0o755)
        do {
          try AtomicFile.write(
            Array(RandomSpheres.sceneText(count: count).utf8), to: path)
        } catch {
          throw Failure(
            description: "cannot write the benchmark scene: \(error)")
        }
      }
      return path
    case .randomMesh(let count):
      let (name, path) = ("mesh-\(count)", "\(dataFolder)/mesh-\(count).txt")
      if access(path, R_OK) != 0 {
        mkdir(dataFolder, 0o755)
        do {
          try AtomicFile.write(
            Array(RandomMesh.objText(count: count).utf8),
            to: "\(dataFolder)/\(name).obj")
          try AtomicFile.write(
            Array(RandomMesh.sceneText(objName: "\(name).obj").utf8), to: path)
        } catch {
          throw Failure(
            description: "cannot write the benchmark scene: \(error)")
        }
      }
      return path
    }
  }

  /// One warm-up run (file cache), then `runs` timed ones, then one run
  /// rendering 2 × `runs` more times after its first for the warm median.
  package func measure(_ workload: Workload) throws -> BenchmarkResult {
    let scene = try scenePath(for: workload)
    let threads = workload.threads ?? Platform.availableCores
    var arguments = [
      scene, "--size", "\(workload.width)", "\(workload.height)",
      "--threads", "\(threads)", "--stats", "--engine", "fast",
    ]
    if workload.samples > 1 {
      arguments += ["--samples", "\(workload.samples)"]
      if workload.samplesAllOutputs { arguments += ["--sample-all-outputs"] }
    }
    let outputFolder = dataFolder + "/out"
    mkdir(dataFolder, 0o755)
    mkdir(outputFolder, 0o755)
    if workload.outputs.contains(.depth) {
      arguments += ["--depth", outputFolder + "/depth.png"]
    }
    if workload.outputs.contains(.normals) {
      arguments += ["--normals", outputFolder + "/normals.png"]
    }
    if workload.outputs.contains(.shaded) {
      arguments += ["-o", outputFolder + "/shaded.png"]
    }
    var renderTimes: [Double] = []
    var wallTimes: [Double] = []
    var peak = 0
    for run in 0...runs {
      let outcome = try Self.spawn(executable, arguments)
      guard outcome.status == 0 else {
        throw Failure(
          description:
            "\(executable) \(arguments.joined(separator: " ")) failed: "
            + outcome.stderr
        )
      }
      guard let seconds = Self.renderSeconds(inStats: outcome.stderr) else {
        throw Failure(
          description: "no 'render:' line in the output of \(executable)")
      }
      peak = max(
        peak, Self.peakBytes(inStats: outcome.stderr) ?? outcome.peakBytes)
      if run > 0 {
        renderTimes.append(seconds)
        wallTimes.append(outcome.wallSeconds)
      }
    }
    // Twice as many warm renders as timed runs: one process's median is
    // noisier than a median over processes on this virtual machine.
    let warm = try Self.spawn(
      executable, arguments + ["--repeat", "\(2 * runs)"])
    guard warm.status == 0,
      let warmSeconds = Self.renderSeconds(inStats: warm.stderr)
    else {
      throw Failure(
        description: "\(executable) --repeat \(2 * runs) failed: \(warm.stderr)"
      )
    }
    return BenchmarkResult(
      workload: workload, scenePath: scene, threads: threads,
      renderSeconds: median(renderTimes), warmRenderSeconds: warmSeconds,
      endToEndSeconds: median(wallTimes), peakBytes: peak,
      objects: Self.objectCount(inStats: warm.stderr))
  }

  struct Outcome {
    var status: Int32
    var stderr: String
    var wallSeconds: Double
    var peakBytes: Int
  }

  /// Runs a child with standard error captured, and its resource usage.
  static func spawn(_ executable: String, _ arguments: [String]) throws
    -> Outcome
  {
    guard let pipe = Platform.makePipe() else {
      throw Failure(description: "pipe failed")
    }
    var clock = Stopwatch()
    let spawned = Platform.spawn(executable, arguments, errorPipe: pipe)
    close(pipe.write)
    guard case .success(let child) = spawned else {
      close(pipe.read)
      if case .failure(let error) = spawned {
        throw Failure(
          description: "cannot start \(executable): "
            + String(cString: strerror(error.code)))
      }
      throw Failure(description: "cannot start \(executable)")
    }
    var captured: [UInt8] = []
    var buffer = [UInt8](repeating: 0, count: 4096)
    while true {
      let count = read(pipe.read, &buffer, buffer.count)
      if count <= 0 { break }
      captured += buffer[0..<count]
    }
    close(pipe.read)
    var usage = rusage()
    var exit: Int32 = 0
    while wait4(child, &exit, 0, &usage) < 0 && errno == EINTR {}
    let wall = clock.lap()
    return Outcome(
      status: (exit & 0x7F) == 0 ? (exit >> 8) & 0xFF : 128 + (exit & 0x7F),
      stderr: String(decoding: captured, as: UTF8.self), wallSeconds: wall,
      peakBytes: Platform.peakBytes(usage))
  }
}
