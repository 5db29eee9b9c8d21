import ExactArithmetic
import FastEngine
import FastKernels
import Geometry
import SceneDescription

/// One row of `raytrace report`: a scene rendered in one precision by one
/// method, its time and its error against the reference.
package struct AccuracyRow: Sendable {
  package var scene: String
  package var precision: Precision
  package var method: ReportedMethod
  package var width: Int
  package var height: Int
  /// The fastest round's median time of one render.
  package var seconds: Double
  /// The median of its time over the naive method's in the same precision,
  /// timed side by side.
  package var timeOverNaive: Double
  package var measurement: AccuracyMeasurement
  /// The precision's unit roundoff's double: 2^−23 or 2^−52.
  package var epsilon: Double

  package var megaraysPerSecond: Double {
    Double(width * height) / seconds / 1e6
  }

  /// How the report renders and times its rows.
  package struct Timing: Sendable {
    package var width: Int
    package var height: Int
    package var threads: Int
    package var runs: Int
    package var rounds: Int

    package init(width: Int, height: Int, threads: Int, runs: Int, rounds: Int)
    {
      self.width = width
      self.height = height
      self.threads = threads
      self.runs = runs
      self.rounds = rounds
    }
  }

  /// The rows of `scene` in `precision`: naive, stable and, in Double where
  /// the course engine draws the scene, the course engine, each measured
  /// against the same camera rays intersected in `reference`.
  package static func measure(
    _ scene: Scene, name: String, precision: Precision,
    reference: ReferencePrecision, timing: Timing
  ) -> [AccuracyRow] {
    let withCourse =
      precision == .double && LengthScale.unscaledFailure(scene) == nil
    // Generic over the reference's scalar, chosen by `reference`.
    func rows<R: RayScalar>(in _: R.Type) -> [AccuracyRow] {
      let wanted = AccuracyRender.reference(
        scene, width: timing.width, height: timing.height, rays: precision,
        threads: timing.threads, in: R.self)
      let renders = AccuracyRender.renderMethods(
        scene, width: timing.width, height: timing.height,
        precision: precision,
        methods: ReportedMethod.all(withCourse: withCourse),
        threads: timing.threads, runs: timing.runs, rounds: timing.rounds)
      return renders.map {
        AccuracyRow(
          scene: name, precision: precision, method: $0.method,
          width: timing.width, height: timing.height, seconds: $0.seconds,
          timeOverNaive: $0.overNaive,
          measurement: $0.buffers.measured(against: wanted),
          epsilon: $0.buffers.epsilon)
      }
    }
    switch reference {
    case .doubleDouble:
      return rows(in: DoubleDouble.self)
    case .float80:
      #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
        return rows(in: Float80.self)
      #else
        preconditionFailure("refused by validate(): no 80-bit type here")
      #endif
    }
  }
}
