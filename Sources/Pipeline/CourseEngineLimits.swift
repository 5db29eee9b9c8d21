import FastEngine
import FastKernels
import SceneDescription

/// What the course engine's own arithmetic cannot hold: it computes with
/// the scene's lengths as they are, in Double, with no rescaling, so a
/// scene the fast engine draws at any scale may be beyond it
/// (`LengthScale.unscaledFailure`). The remedy is the fast engine
/// (`Remedy.fastEngine`).
package enum CourseEngineLimits {
  /// Why the course engine cannot draw `scene` right, or nil.
  package static func problem(_ scene: Scene) -> String? {
    LengthScale.unscaledFailure(scene).map {
      "the course engine, which computes with the scene's own lengths, "
        + "cannot draw \($0.failure.object): \($0.failure.measure) is "
        + ($0.beyondRange
          ? "beyond double's range" : "below double's normal range")
    }
  }
}
