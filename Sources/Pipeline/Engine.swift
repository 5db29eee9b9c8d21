import Geometry
import FastEngine

/// The two renderers, which draw the same scene within a stated bound
/// (docs/ENGINES.md).
package enum Engine: String, CaseIterable, Sendable {
  /// `CourseEngine` (the course target): the course's loop over every
  /// object by the hit protocol, in Double. The default (`Engine.default`):
  /// the code a student reads and edits.
  case course
  /// `Renderer`: the scene compiled into flat records for one precision,
  /// searched through screen tiles or a hierarchy; exact at any scale.
  case fast
}

extension Engine {
  /// The engine a render uses when none is named and no option asks for
  /// the fast engine's own choices: the one place it is set.
  package static let `default` = Engine.course
}

/// A render as the command line asks for it: the image, the engine that
/// draws it, the fast engine's options, and how often to draw it.
package struct RenderRequest: Sendable {
  package var settings: RenderSettings
  package var engine: Engine
  /// Used when `engine` is `.fast`: the course engine computes in Double by
  /// its own method.
  package var fast: FastOptions
  /// Renders of the same image after the first, in the same process: the
  /// render time reported is then their median, a warm render as peers
  /// that time repeated renders report it (`raytrace bench`). The files
  /// are written once.
  package var repeats = 0

  package init(
    _ settings: RenderSettings, engine: Engine = .default,
    fast: FastOptions = FastOptions()
  ) {
    self.settings = settings
    self.engine = engine
    self.fast = fast
  }
}
