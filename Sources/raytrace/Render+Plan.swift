import Dispatch
import ArgumentParser
import enum Course.CourseEngine
import enum Course.CourseShapes
import FastEngine
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// The options checked and turned into what a render needs: the scene's
/// path, the request (image, engine, the fast engine's options, repeats),
/// the files and the depth range.
extension Render {
  /// The checked form of the options, made in `validate()`.
  struct Plan {
    var scenePath: String
    var request: RenderRequest
    var settings: RenderSettings { request.settings }
    var files: [OutputFile]
    var depthRange: ClosedRange<Double>?
  }

  mutating func validate() throws {
    guard !Raytrace.defersValidation else { return }
    _ = try plan()
  }

  func plan() throws -> Plan {
    let scenePath: String
    switch (scene, input) {
    case (let path?, nil), (nil, let path?): scenePath = path
    case (nil, nil): throw ValidationError("Missing the scene file.")
    case (_?, _?):
      throw ValidationError(
        "Give the scene either as an argument or with -input, not both.")
    }
    var width = 800
    var height = 800
    if !size.isEmpty {
      guard size.count == 2 else {
        throw ValidationError(
          "--size takes two values, W and H; got \(size.count).")
      }
      (width, height) = (size[0], size[1])
      guard width >= 1, height >= 1 else {
        throw ValidationError(
          "--size needs W and H of at least 1; got \(width) \(height).")
      }
    }
    var range: ClosedRange<Double>?
    var depthPath = depth
    if !assignmentDepth.isEmpty {
      guard depth == nil else {
        throw ValidationError(
          "Give the depth image either with --depth or with -depth, not both.")
      }
      guard assignmentDepth.count == 3, let low = Double(assignmentDepth[0]),
        let high = Double(assignmentDepth[1])
      else {
        throw ValidationError("-depth takes three values: MIN MAX FILE.")
      }
      range = try checkedRange(low, high, option: "-depth")
      depthPath = assignmentDepth[2]
    }
    if !depthRange.isEmpty {
      guard range == nil else {
        throw ValidationError(
          "-depth already gives a range; drop --depth-range.")
      }
      guard depthRange.count == 2 else {
        throw ValidationError("--depth-range takes two values, MIN and MAX.")
      }
      range = try checkedRange(
        depthRange[0], depthRange[1], option: "--depth-range")
    }
    var files: [OutputFile] = []
    for (kind, path) in [
      (RenderOutputs.shaded, output), (.depth, depthPath), (.normals, normals),
    ] {
      guard let path else { continue }
      guard let file = OutputFile(kind: kind, path: path) else {
        throw ValidationError(
          "Cannot tell the format of '\(Self.escaped(path))': use .png, .ppm, "
            + ".pfm or .npy."
        )
      }
      files.append(file)
    }
    guard !files.isEmpty || check else {
      throw ValidationError(
        "Nothing to render: give at least one of -o, --depth or --normals.")
    }
    if check, engine != nil {
      throw ValidationError(
        "--check renders with both engines: drop --engine.")
    }
    try Self.checkDistinct(files, scenePath: scenePath)
    try checkMemory(width: width, height: height, files: files)
    if let threads, threads < 1 {
      throw ValidationError("--threads must be at least 1; got \(threads).")
    }
    guard (0...9).contains(pngLevel) else {
      throw ValidationError(
        "--png-level must be between 0 and 9; got \(pngLevel).")
    }
    let strata = Int(Double(max(samples, 0)).squareRoot())
    guard samples >= 1, samples <= 4096, strata * strata == samples else {
      throw ValidationError(
        "--samples must be a square between 1 and 4096 (1, 4, 9, 16, ...); got "
          + "\(samples)."
      )
    }
    var settings = RenderSettings(
      width: width, height: height, outputs: [],
      style: style ?? (input != nil ? .mit : .course),
      threads: threads ?? Platform.availableCores)
    settings.samples = samples
    settings.filter = filter
    settings.samplesAllOutputs = sampleAllOutputs
    var request = RenderRequest(
      settings,
      fast: FastOptions(
        precision: precision ?? .double, method: intersection ?? .stable))
    // The course engine computes in double by the stable quadratic: a
    // request for float or naive asks for the fast engine, unless the
    // course engine is named.
    let fastOnly = precision == .float || intersection == .naive
    switch engine {
    case .course? where precision == .float:
      throw ValidationError(
        "--engine course computes in double, the scene's precision; drop "
          + "--precision float or use --engine fast.")
    case .course? where intersection == .naive:
      throw ValidationError(
        "--engine course solves the sphere's quadratic one way (stable); "
          + "drop --intersection naive or use --engine fast.")
    case let engine?: request.engine = engine
    case nil: request.engine = fastOnly && !check ? .fast : .default
    }
    guard (0...1000).contains(repeats) else {
      throw ValidationError(
        "--repeat must be between 0 and 1000; got \(repeats).")
    }
    request.repeats = repeats
    return Plan(
      scenePath: scenePath, request: request, files: files, depthRange: range)
  }
}
