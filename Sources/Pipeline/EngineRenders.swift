import Course
import FastEngine
import Geometry
import SceneDescription

/// `--check`'s renders: each engine once, every output kept, in Double.
package enum EngineRenders {
  /// The course engine's buffers and the fast engine's (in the request's
  /// precision and method, widened to Double) for `settings`' outputs.
  package static func render(
    _ scene: Scene, request: RenderRequest, textures: [Texture?]
  ) -> (course: RenderBuffers<Double>, fast: RenderBuffers<Double>) {
    let course = CourseEngine.render(
      scene, textures: textures, settings: request.settings)
    let fast = FastScene(
      scene, textures: textures, options: request.fast,
      threads: request.settings.threads
    ).render(request.settings).buffers.doubles
    return (course, fast)
  }
}
