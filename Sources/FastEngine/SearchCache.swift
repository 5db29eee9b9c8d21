import Geometry
import PlatformSupport

/// What one compiled scene's renders keep for the next (`FastScene` holds
/// one): the hierarchies, which do not depend on the view, built the first
/// time a render needs them and never again; and the screen tiles of the
/// last view, which a render of the same view (repeated, as a program
/// that redraws its window) reuses rather than boxing and sorting every
/// primitive again. The peer's warm render likewise traverses a hierarchy
/// built while loading the scene.
///
/// Both are what `Renderer` would build afresh, bit for bit: the tiles
/// depend only on the scene, which is fixed, and on `View`, and neither
/// depends on the threads that build them (`TileListsTests`).
package final class SearchCache<Kernel: IntersectionKernel>: Sendable {
  /// What a render's tiles depend on besides the scene.
  struct View: Equatable {
    var style: ImageStyle
    var width: Int
    var height: Int
    var sampleMargin: Double
    var overlapLimit: Int

    init(_ settings: RenderSettings, overlapLimit: Int) {
      style = settings.style
      width = settings.width
      height = settings.height
      sampleMargin = settings.sampleMargin
      self.overlapLimit = overlapLimit
    }
  }

  private struct State {
    /// The last view's search: its tiles, or nil where they were declined
    /// (the scene then searched by its hierarchies).
    var view: View?
    var tiles: ScreenTiles<Kernel>?
    /// The scene with its hierarchies built and its records in their
    /// order.
    var hierarchical: CompiledScene<Kernel>?
  }

  private let state = Locked(State())

  package init() {}

  /// The scene to render and its tiles for `settings`: cached, or built
  /// and kept. Renders of one scene wait for each other here while one
  /// builds.
  func search(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings, overlapLimit: Int
  ) -> (scene: CompiledScene<Kernel>, tiles: ScreenTiles<Kernel>?) {
    let view = View(settings, overlapLimit: overlapLimit)
    return state.withLock { state in
      if state.view != view {
        state.tiles = Renderer.tiles(
          scene, settings: settings, overlapLimit: overlapLimit)
        state.view = view
      }
      if let tiles = state.tiles { return (scene, tiles) }
      let hierarchical = state.hierarchical ?? Renderer.hierarchical(scene)
      state.hierarchical = hierarchical
      return (hierarchical, nil)
    }
  }
}
