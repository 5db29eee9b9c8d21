import RealModule
import FastEngine
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// How far a supersampled shaded image is from a reference with many more
/// samples: the error antialiasing leaves, in the displayed (clamped)
/// colour.
package struct AntialiasingMeasurement: Sendable {
  /// Root mean square over pixels and channels, colour in [0, 1].
  package var rootMeanSquare: Double
  /// The largest difference of any channel, in 8-bit levels.
  package var maxLevels: Double

  package init(_ image: [RGB<Double>], against reference: [RGB<Double>]) {
    precondition(image.count == reference.count)
    var squares = 0.0
    var largest = 0.0
    for (a, b) in zip(image, reference) {
      let difference = a.clampedToUnit() - b.clampedToUnit()
      squares += difference.lengthSquared
      largest = Swift.max(largest, difference.maxMagnitude)
    }
    rootMeanSquare = (squares / Double(Swift.max(3 * image.count, 1)))
      .squareRoot()
    maxLevels = largest * 255
  }

  /// The shaded image of `scene` with `samples` rays per pixel (stable,
  /// Double) and the median time of `runs` renders after a warm-up.
  package static func render(
    _ scene: Scene, width: Int, height: Int, samples: Int,
    filter: PixelFilter = .box,
    threads: Int, runs: Int
  ) -> (color: [RGB<Double>], medianSeconds: Double) {
    var settings = RenderSettings(
      width: width, height: height, outputs: [.shaded], threads: threads)
    settings.samples = samples
    settings.filter = filter
    let compiled = FastScene(scene, options: FastOptions())
    var buffers = compiled.render(settings).buffers
    var times: [Double] = []
    for _ in 0..<runs {
      var clock = Stopwatch()
      buffers = compiled.render(settings).buffers
      times.append(clock.lap())
    }
    return (buffers.doubles.color, runs > 0 ? median(times) : .nan)
  }
}

/// One antialiasing row of `raytrace report`: a scene's shaded image with
/// `samples` rays per pixel against 1,024.
package struct AntialiasingRow: Sendable {
  package var scene: String
  package var width: Int
  package var height: Int
  package var samples: Int
  /// The median time of one render.
  package var seconds: Double
  package var measurement: AntialiasingMeasurement

  /// The samples per pixel of the rows, and of the reference.
  package static let sampleCounts = [1, 4, 16, 64]
  package static let referenceSamples = 1024

  /// The rows of `scene` at `width` × `height` (the report takes half its
  /// size: the reference is a thousand renders).
  package static func measure(
    _ scene: Scene, name: String, width: Int, height: Int, threads: Int,
    runs: Int
  ) -> [AntialiasingRow] {
    let (reference, _) = AntialiasingMeasurement.render(
      scene, width: width, height: height, samples: referenceSamples,
      threads: threads, runs: 0)
    return sampleCounts.map { samples in
      let (color, seconds) = AntialiasingMeasurement.render(
        scene, width: width, height: height, samples: samples,
        threads: threads, runs: runs)
      return AntialiasingRow(
        scene: name, width: width, height: height, samples: samples,
        seconds: seconds,
        measurement: AntialiasingMeasurement(color, against: reference))
    }
  }
}
