import ExactArithmetic
import Course
import FastEngine
import FastKernels
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

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
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals], style: style,
      threads: threads)
    let render = prepared(
      scene, settings: settings, precision: precision, method: method)
    guard runs > 0 else { return (render.buffers, .nan) }
    return (render.buffers, median((0..<runs).map { _ in render.time() }))
  }

  /// Depth and normals of `scene` by each of `methods` in `precision`,
  /// timed in alternation: `rounds` rounds, each compiling the scene afresh
  /// for every method and then timing `runs` renders of each in turn (the
  /// order reversed every other run). A method's time is the fastest of its
  /// rounds' medians; its time over naive's is the median of the ratios of
  /// renders timed side by side, over every run of every round. Both meet
  /// the same load on a shared machine: a slow spell slows both of a pair,
  /// and a compile whose buffers landed where they run slowly (seen here:
  /// a whole round of one method 20% slower, and the next compile of it
  /// not) moves one round's ratios, not their median (`raytrace report`'s
  /// "÷ naive" column).
  package static func renderMethods(
    _ scene: Scene, width: Int, height: Int, precision: Precision,
    methods: [ReportedMethod], threads: Int = 1, runs: Int = 1,
    rounds: Int = 1
  ) -> [TimedMethod] {
    precondition(methods.first == .fast(.naive), "naive is the yardstick")
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals],
      style: .course, threads: threads)
    // Every round's buffers are the same (the renderers are
    // deterministic): the first round's are kept.
    var buffers: [AnyRenderBuffers] = []
    var fastest = [Double](repeating: .infinity, count: methods.count)
    var ratios = [[Double]](repeating: [], count: methods.count)
    for round in 0..<rounds {
      let renders = methods.map {
        prepared(scene, settings: settings, precision: precision, method: $0)
      }
      if round == 0 { buffers = renders.map(\.buffers) }
      var times = [[Double]](repeating: [], count: methods.count)
      for run in 0..<runs {
        var order = Array(methods.indices)
        if run % 2 == 1 { order.reverse() }
        var seconds = [Double](repeating: 0, count: methods.count)
        for index in order { seconds[index] = renders[index].time() }
        for index in methods.indices {
          times[index].append(seconds[index])
          ratios[index].append(seconds[index] / seconds[0])
        }
      }
      for index in methods.indices {
        fastest[index] = Swift.min(fastest[index], median(times[index]))
      }
    }
    return methods.indices.map {
      TimedMethod(
        method: methods[$0], buffers: buffers[$0], seconds: fastest[$0],
        overNaive: median(ratios[$0]))
    }
  }

  /// One method's render and times, as `renderMethods` measured them.
  package struct TimedMethod {
    package var method: ReportedMethod
    package var buffers: AnyRenderBuffers
    /// The fastest round's median time of one render.
    package var seconds: Double
    /// The median of its times over naive's, taken side by side.
    package var overNaive: Double
  }

  /// A scene's first render (a warm-up, whose buffers are every render's:
  /// the renderers are deterministic) and the timer of one more. Compiling
  /// the scene is not timed.
  private struct TimedRender {
    var buffers: AnyRenderBuffers
    var time: () -> Double
  }

  private static func prepared(
    _ scene: Scene, settings: RenderSettings, precision: Precision,
    method: ReportedMethod
  ) -> TimedRender {
    switch method {
    case .fast(let method):
      return prepared(
        scene, settings: settings, precision: precision, method: method)
    case .course:
      // The course engine as a student's code runs it: Double, the
      // scene's own lengths, the hit protocol.
      precondition(precision == .double, "the course engine is Double")
      let buffers = CourseEngine.render(scene, settings: settings)
      return TimedRender(buffers: .double(buffers)) {
        var clock = Stopwatch()
        _ = CourseEngine.render(scene, settings: settings)
        return clock.lap()
      }
    }
  }

  private static func prepared(
    _ scene: Scene, settings: RenderSettings, precision: Precision,
    method: IntersectionMethod
  ) -> TimedRender {
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
