import ArgumentParser
import FastEngine
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// What the command line is checked for before anything is rendered:
/// outputs by identity, the image's memory, depth ranges.
extension Render {
  /// Two outputs naming one file, or an output naming the scene, are
  /// usage errors: compared by identity (`FileIdentity`), not spelling.
  static func checkDistinct(
    _ files: [OutputFile], scenePath: String
  ) throws {
    for (index, file) in files.enumerated() {
      if FileIdentity.same(file.path, scenePath) {
        throw ValidationError(
          "\(name(of: file)) would overwrite the scene file "
            + "'\(escaped(scenePath))'."
        )
      }
      for other in files[..<index]
      where FileIdentity.same(file.path, other.path) {
        throw ValidationError(
          "\(name(of: other)) and \(name(of: file)) name the same file.")
      }
    }
  }

  /// An output as the command line gave it, for messages.
  static func name(of file: OutputFile) -> String {
    let option =
      file.kind == .depth
      ? "--depth" : file.kind == .normals ? "--normals" : "-o"
    return "\(option) '\(escaped(file.path))'"
  }

  static func escaped(_ path: String) -> String {
    SceneParser.escaped(path)
  }

  /// An output naming a file the scene reads (a mesh or a texture) is a
  /// usage error, found once the scene is read: nothing is rendered.
  func checkOutputs(_ files: [OutputFile], against scene: Scene) throws
  {
    let inputs = scene.meshFiles + scene.materials.compactMap(\.texturePath)
    for file in files {
      for input in inputs where FileIdentity.same(file.path, input) {
        printError(
          "raytrace: error: \(Self.name(of: file)) would overwrite "
            + "'\(Self.escaped(input))', which the scene reads."
        )
        throw ExitCode.validationFailure
      }
    }
  }

  /// The largest image: 32768 on a side and 2²⁸ pixels (the buffers of a
  /// double render with every output are then about 17 GiB).
  static let maximumSide = 32768
  static let maximumPixels = 1 << 28

  /// Refuses, before anything is allocated, an image whose buffers would
  /// not fit: beyond the fixed limits of size, or beyond what the process
  /// may use (`Memory.limits`), saying how much it would need.
  func checkMemory(width: Int, height: Int, files: [OutputFile]) throws {
    let bytes = Double(width) * Double(height) * Self.bytesPerPixel(files)
    let gib = { (bytes: Double) in
      "\(formatted(bytes / 1_073_741_824, digits: 3)) GiB"
    }
    let (pixels, overflow) = width.multipliedReportingOverflow(by: height)
    guard
      !overflow && width <= Self.maximumSide && height <= Self.maximumSide
        && pixels <= Self.maximumPixels
    else {
      throw ValidationError(
        "--size \(width) \(height) would need about \(gib(bytes)) "
          + "of memory; the limit is \(Self.maximumSide) pixels on a side and "
          + "\(Self.maximumPixels) pixels in all.")
    }
  }

  /// The machine's limit rather than a usage error: an image whose buffers
  /// and files need more memory than the process may use (an address-space
  /// limit, say), as one line for `raytrace: error:`; nil when it fits or
  /// nothing says.
  static func memoryLimitProblem(
    width: Int, height: Int, files: [OutputFile]
  ) -> String? {
    let bytes = Double(width) * Double(height) * bytesPerPixel(files)
    // What the program takes before any image: its code, libraries,
    // threads' stacks (all counted by an address-space limit).
    let baseline = 384.0 * 1_048_576
    guard let limit = Memory.limits().first,
      bytes + baseline > Double(limit.bytes)
    else { return nil }
    let gib = { (bytes: Double) in
      "\(formatted(bytes / 1_073_741_824, digits: 3)) GiB"
    }
    return "--size \(width) \(height) would need about "
      + "\(gib(bytes + baseline)) of memory for these outputs, and the "
      + "process may use at most \(gib(Double(limit.bytes))) (\(limit.what))."
  }

  /// The memory a pixel takes, at most: the engine's buffers in Double
  /// (the course engine's, or the fast engine's in its precision) and each
  /// file as encoded (8-bit pixels and their PNG; raw values as written).
  static func bytesPerPixel(_ files: [OutputFile]) -> Double {
    var total = 0.0
    for file in files {
      let channels = file.kind == .depth ? 1.0 : 3.0
      total += 8 * channels
      switch file.format {
      case .png: total += 6
      case .ppm: total += 3
      case .pfm: total += 4 * channels
      case .npy: total += 8 * channels
      }
    }
    return total
  }

  func checkedRange(_ low: Double, _ high: Double, option: String)
    throws -> ClosedRange<Double>
  {
    guard low.isFinite, high.isFinite, low < high else {
      throw ValidationError(
        "\(option) needs finite MIN < MAX; got \(low) \(high).")
    }
    return low...high
  }

  /// Whether the folders have room for the files whose size is known
  /// before rendering (PPM, PFM, NPY: their size is the image's; a PNG's
  /// is not known, and is not counted): a full disk found now, not after
  /// the render. Nil when there is room, or the system does not say.
  static func roomProblem(_ plan: Plan) -> String? {
    let pixels = plan.settings.width * plan.settings.height
    var needs: [String: (bytes: Int, example: String)] = [:]
    for file in plan.files {
      let channels = file.kind == .depth ? 1 : 3
      let scalar = plan.request.fast.precision == .float ? 4 : 8
      let bytes: Int
      switch file.format {
      case .png: continue
      case .ppm: bytes = 3 * pixels + 32
      case .pfm: bytes = 4 * channels * pixels + 32
      case .npy: bytes = scalar * channels * pixels + 128
      }
      let slash = file.path.lastIndex(of: "/")
      let folder = slash.map { String(file.path[...$0]) } ?? "."
      needs[folder, default: (0, file.path)].bytes += bytes
    }
    for (folder, need) in needs.sorted(by: { $0.key < $1.key }) {
      guard let free = Platform.freeBytes(inFolder: folder), need.bytes > free
      else { continue }
      return "cannot write '\(escaped(need.example))': the outputs in its "
        + "folder need \(need.bytes) bytes, and its file system has "
        + "\(free) free"
    }
    return nil
  }
}
