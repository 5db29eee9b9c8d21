import Geometry
import SceneDescription

extension CourseEngine {
  /// The ray of pixel (`column`, `row`) and what each object of the scene's
  /// group gives for it: its index in the group and its hit, for the
  /// objects that are hit. The engines' check names the object the course
  /// engine hit at a pixel where the engines differ with this.
  package static func probe(
    _ scene: Scene, settings: RenderSettings, column: Int, row: Int
  ) -> (ray: Ray<Double>, hits: [(index: Int, hit: Hit<Double>)]) {
    let view = View(scene, textures: [], settings: settings)
    let ray = view.ray(column: column, row: row)
    var hits: [(index: Int, hit: Hit<Double>)] = []
    for (index, object) in scene.root.objects.enumerated() {
      if let hit = SceneObjects.object(object)?.intersect(
        ray, after: 0, before: .infinity)
      {
        hits.append((index, hit))
      }
    }
    return (ray, hits)
  }
}
