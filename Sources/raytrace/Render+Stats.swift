import ArgumentParser
import FastEngine
import Pipeline
import Measurement
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// `--stats`: what a render did, on standard error.
extension Render {
  func printStats(
    _ report: RenderReport, scenePath: String, parseSeconds: Double
  ) {
    let settings = report.settings
    let request = report.request
    printError(
      "scene: \(scenePath): \(report.spheres) spheres, \(report.planes) "
        + "planes, "
        + "\(report.triangles) triangles, \(report.ellipsoids) transformed "
        + "spheres; "
        + "nearest sphere by "
        + (report.sphereSearch.map { "\($0)" }
          ?? "the course engine, every object") + ", "
        + "nearest triangle by \(report.triangleSearch)"
    )
    printError(
      "size: \(settings.width)x\(settings.height), \(report.rays) rays, "
        + "precision \(request.fast.precision.rawValue), intersection "
        + "\(request.fast.method.rawValue), "
        + "engine \(request.engine.rawValue), "
        + "style \(settings.style.rawValue), threads \(settings.threads)")
    printError(
      "outputs: \(settings.outputs.names.joined(separator: ", "))"
        + "; left out: "
        + (report.leftOut.isEmpty
          ? "nothing" : report.leftOut.joined(separator: ", "))
    )
    if report.texturedMaterials > 0 {
      printError(
        report.texturesRead > 0
          ? "textures: \(report.texturesRead) read for the shaded image"
          : "textures: none read (no shaded image is requested)")
    }
    if let range = report.depthRange {
      printError("depth range: \(range.lowerBound) to \(range.upperBound)")
    }
    printError("parse: \(seconds(parseSeconds))")
    printError("compile: \(seconds(report.compileSeconds))")
    let repeats = request.repeats
    printError(
      "render: \(seconds(report.renderSeconds)), "
        + "\(formatted(report.megaraysPerSecond, digits: 3)) Mrays/s"
        + (repeats > 0
          ? " (median of \(repeats) repeated renders; first render "
            + "\(seconds(report.firstRenderSeconds)))"
          : ""))
    printError("write: \(seconds(report.writeSeconds))")
    if let peak = Memory.ownPeakBytes() {
      // The bench reads it: its own children's `wait4` figures carry the
      // bench's peak on Linux (`Memory.ownPeakBytes`).
      printError(
        "peak memory: \(formatted(Double(peak) / 1_048_576, digits: 4)) MiB")
    }
  }
}
