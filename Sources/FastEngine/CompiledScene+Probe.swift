import Geometry
import SceneDescription

/// What the fast engine hits along one ray from the eye, object by object
/// of the scene's group: how the engines' check names the object the
/// fast engine's pixel shows, from its own hits.
extension CompiledScene {
  /// Each object of `scene`'s group that the ray from the eye in
  /// `direction` hits, compiled on its own in this kernel's precision:
  /// its index in the group, t in the world's units along `direction`,
  /// and the hit's material.
  package static func objectHits(
    _ scene: Scene, direction: Vector3<Double>
  ) -> [(index: Int, t: Double, materialIndex: Int)] {
    var hits: [(index: Int, t: Double, materialIndex: Int)] = []
    for (index, object) in scene.root.objects.enumerated() {
      var single = scene
      single.root = Group([object])
      let compiled = CompiledScene(single)
      let ray = CameraRay(
        origin: compiled.rayOrigin, direction: Vector3<Scalar>(direction))
      let own = compiled.nearest(ray)
      if let (layer, hit, layerRay) = compiled.nearerInLayers(ray, than: own) {
        let scene = compiled.layers[layer]
        hits.append(
          (
            index, Double(hit.t * scene.lengthScale),
            scene.materialIndex(of: hit.what, layerRay)
          ))
      } else if let own {
        hits.append(
          (
            index, Double(own.t * compiled.lengthScale),
            compiled.materialIndex(of: own.what, ray)
          ))
      }
    }
    return hits
  }
}
