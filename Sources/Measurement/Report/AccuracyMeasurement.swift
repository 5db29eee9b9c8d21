import RealModule
import FastEngine
import SceneIO
import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// How far a render's depth and normals are from the reference path's, per
/// pixel and in summary.
///
/// The reference intersects the very rays the render traced (generated in
/// the render's precision, converted exactly) in `ReferenceScalar` (Float80
/// on x86, 64-bit significand; `DoubleDouble`, 106 bits, where there is no
/// Float80) with the stable camera-relative method, its
/// constants computed from the scene's Double values in twice Double's
/// precision. What is measured is therefore the error of the intersection,
/// not a difference in where the camera's rays point.
package struct AccuracyMeasurement: Sendable {
  /// Pixels where both hit something.
  package var comparedHits: Int
  /// max |t − t_ref| / t_ref over compared hits.
  package var maxRelativeError: Double
  /// The 99th percentile of the same.
  package var p99RelativeError: Double
  /// The largest relative error of t away from silhouettes: over pixels
  /// whose eight neighbours in the reference all hit, at depths within 10%
  /// of the pixel's and with normals within 10° of its. Near a silhouette
  /// the ray is almost tangent and t is ill-conditioned (a rounding in the
  /// discriminant moves it by √ε), so the plain maximum measures the
  /// problem rather than the method.
  package var maxInteriorRelativeError: Double
  /// Pixels where one hit and the other missed.
  package var disagreements: Int
  /// The largest angle between normals over compared hits, in degrees.
  package var maxNormalErrorDegrees: Double
  /// Relative error of t per pixel, row 0 at the top: NaN where both
  /// missed, +inf where they disagree.
  package var perPixel: [Double]

  /// Compares `buffers` (depth and normals) with `reference`.
  package init<S: RayScalar, R: RayScalar>(
    _ buffers: RenderBuffers<S>, against reference: RenderBuffers<R>
  ) {
    precondition(buffers.depth.count == reference.depth.count)
    var errors: [Double] = []
    var perPixel = [Double](repeating: .nan, count: buffers.depth.count)
    var disagreements = 0
    var maxAngle = 0.0
    let hasNormals = !buffers.normals.isEmpty && !reference.normals.isEmpty
    // Converted once: the interior test below reads each up to 18 times,
    // and a generic conversion from a DoubleDouble reference is slow.
    let referenceNormals = reference.normals.map { Vector3<Double>($0) }
    for pixel in buffers.depth.indices {
      let t = buffers.depth[pixel]
      let want = reference.depth[pixel]
      switch (t.isFinite, want.isFinite) {
      case (false, false):
        continue
      case (true, true):
        let error = Double((R(t) - want).magnitude / want)
        errors.append(error)
        perPixel[pixel] = error
        if hasNormals {
          maxAngle = Swift.max(
            maxAngle,
            angleInDegrees(
              Vector3<Double>(buffers.normals[pixel]),
              referenceNormals[pixel]))
        }
      default:
        disagreements += 1
        perPixel[pixel] = .infinity
      }
    }
    var interior = 0.0
    let (width, height) = (buffers.width, buffers.height)
    for row in 1..<Swift.max(1, height - 1) {
      pixels: for column in 1..<Swift.max(1, width - 1) {
        let pixel = row * width + column
        let centre = reference.depth[pixel]
        guard centre.isFinite, perPixel[pixel].isFinite else { continue }
        for dy in -1...1 {
          for dx in -1...1 {
            let neighbour = reference.depth[pixel + dy * width + dx]
            guard neighbour.isFinite,
              (neighbour - centre).magnitude <= centre / 10
            else {
              continue pixels
            }
            if hasNormals {
              let a = referenceNormals[pixel]
              let b = referenceNormals[pixel + dy * width + dx]
              // cos 10° = 0.985
              guard a.dot(b) >= 0.985 else { continue pixels }
            }
          }
        }
        interior = Swift.max(interior, perPixel[pixel])
      }
    }
    maxInteriorRelativeError = interior
    errors.sort()
    comparedHits = errors.count
    maxRelativeError = errors.last ?? 0
    p99RelativeError =
      errors.isEmpty
      ? 0 : errors[Swift.min(errors.count - 1, (errors.count * 99) / 100)]
    self.disagreements = disagreements
    maxNormalErrorDegrees = maxAngle
    self.perPixel = perPixel
  }
}

/// The angle between two vectors in degrees, by atan2(|a × b|, a·b): exact
/// for small angles, where acos(a·b) loses half the digits.
func angleInDegrees(_ a: Vector3<Double>, _ b: Vector3<Double>) -> Double {
  let cross = a.cross(b).length
  return Double.atan2(y: cross, x: a.dot(b)) * 180 / .pi
}

/// Renders for the accuracy report and the stiff-suite tests.
package enum AccuracyRender {
  /// Depth and normals of `scene` by the chosen precision and method, and
  /// the median time of `runs` renders after one warm-up (compiling the
  /// scene is not timed).
  package static func render(
    _ scene: Scene, width: Int, height: Int, precision: Precision,
    method: IntersectionMethod, style: ImageStyle = .course, threads: Int = 1,
    runs: Int = 1
  ) -> (buffers: AnyRenderBuffers, medianSeconds: Double) {
    let render = prepared(
      scene, width: width, height: height, precision: precision,
      method: method, style: style, threads: threads)
    guard runs > 0 else { return (render.buffers, .nan) }
    return (render.buffers, median((0..<runs).map { _ in render.time() }))
  }

  /// Depth and normals of `scene` by each method in `precision`, timed in
  /// alternation: `rounds` rounds, each compiling the scene afresh for
  /// every method in turn and taking the median of `runs` renders, and
  /// each method's time the fastest of its rounds' medians. Both methods
  /// meet the same load on a shared machine, and the minimum leaves out
  /// rounds another process disturbed, or whose compiled scene and
  /// buffers landed where they run slowly (seen here: a whole round of
  /// one method 20% slower, and the next compile of it not), so their
  /// ratio is steadier than that of two single medians (`raytrace
  /// report`'s "÷ naive" column).
  package static func renderMethods(
    _ scene: Scene, width: Int, height: Int, precision: Precision,
    threads: Int = 1, runs: Int = 1, rounds: Int = 1
  ) -> [(
    method: IntersectionMethod, buffers: AnyRenderBuffers, seconds: Double
  )] {
    let methods = IntersectionMethod.allCases
    // Every round's buffers are the same (the renderer is deterministic):
    // the first round's are kept.
    var buffers: [AnyRenderBuffers] = []
    var fastest = [Double](repeating: .infinity, count: methods.count)
    for round in 0..<rounds {
      for (index, method) in methods.enumerated() {
        let render = prepared(
          scene, width: width, height: height, precision: precision,
          method: method, threads: threads)
        if round == 0 { buffers.append(render.buffers) }
        let seconds = median((0..<runs).map { _ in render.time() })
        fastest[index] = Swift.min(fastest[index], seconds)
      }
    }
    return methods.indices.map { (methods[$0], buffers[$0], fastest[$0]) }
  }

  /// A compiled scene's first render (a warm-up, whose buffers are every
  /// render's: the renderer is deterministic) and the timer of one more.
  /// Compiling the scene is not timed.
  private struct TimedRender {
    var buffers: AnyRenderBuffers
    var time: () -> Double
  }

  private static func prepared(
    _ scene: Scene, width: Int, height: Int, precision: Precision,
    method: IntersectionMethod, style: ImageStyle = .course, threads: Int
  ) -> TimedRender {
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals], style: style,
      threads: threads)
    let compiled = FastScene(
      scene, options: FastOptions(precision: precision, method: method))
    return TimedRender(buffers: compiled.render(settings).buffers) {
      var clock = Stopwatch()
      _ = compiled.render(settings)
      return clock.lap()
    }
  }

  /// The reference for renders in `precision`: the same camera rays,
  /// intersected in ReferenceScalar.
  package static func reference(
    _ scene: Scene, width: Int, height: Int, rays precision: Precision,
    style: ImageStyle = .course, threads: Int = 1
  ) -> RenderBuffers<ReferenceScalar> {
    reference(
      scene, width: width, height: height, rays: precision, style: style,
      threads: threads, in: ReferenceScalar.self)
  }

  /// The same reference intersected in `R`: on x86 the tests and `raytrace
  /// report --reference` run it in DoubleDouble, the reference of platforms
  /// without Float80, as well as in Float80.
  package static func reference<R: RayScalar>(
    _ scene: Scene, width: Int, height: Int, rays precision: Precision,
    style: ImageStyle = .course, threads: Int = 1, in _: R.Type
  ) -> RenderBuffers<R> {
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals], style: style,
      threads: threads)
    return FastScene.reference(
      scene, settings: settings, rays: precision, in: R.self)
  }
}

/// The report's measure of either render precision's buffers.
extension AnyRenderBuffers {
  package func measured<R: RayScalar>(
    against reference: RenderBuffers<R>
  ) -> AccuracyMeasurement {
    switch self {
    case .float(let buffers): AccuracyMeasurement(buffers, against: reference)
    case .double(let buffers): AccuracyMeasurement(buffers, against: reference)
    }
  }

  /// The unit roundoff's double, ε = 2^−23 or 2^−52: errors are reported
  /// in units of it.
  package var epsilon: Double {
    switch self {
    case .float: Double(Float.ulpOfOne)
    case .double: Double.ulpOfOne
    }
  }
}

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
