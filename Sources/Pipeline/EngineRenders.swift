import Course
import FastEngine
import Geometry
import Numerics
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
    let fast = try! request.fast.withKernel(
      FastBuffers(scene: scene, textures: textures, settings: request.settings))
    return (course, fast)
  }

  /// The fast engine's buffers as Double.
  private struct FastBuffers: KernelBody {
    var scene: Scene
    var textures: [Texture?]
    var settings: RenderSettings

    func run<Kernel: IntersectionKernel>(_: Kernel.Type)
      -> RenderBuffers<Double>
    {
      let buffers = Renderer.render(
        CompiledScene<Kernel>(scene, textures: textures), settings: settings)
      return RenderBuffers(
        width: buffers.width, height: buffers.height,
        depth: buffers.depth.map(Double.init),
        normals: buffers.normals.map(Vector3<Double>.init),
        color: buffers.color.map(Vector3<Double>.init))
    }
  }
}
