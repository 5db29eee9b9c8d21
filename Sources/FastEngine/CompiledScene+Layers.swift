import Geometry

/// The search of a scene's layers: objects its common scale cannot hold,
/// traced at their own (`LengthScale.layers`).
extension CompiledScene {
  /// The nearest hit among the layers that is nearer than `hit` (a hit of
  /// this scene's own search), compared in the world's units: its layer,
  /// the hit in that layer's units and the ray in its frame; nil when
  /// none is nearer. At equal world t this scene's hit stays, then the
  /// earlier layer's.
  func nearerInLayers(
    _ ray: CameraRay<Scalar>, than hit: (t: Scalar, what: Nearest)?
  ) -> (layer: Int, hit: (t: Scalar, what: Nearest), ray: CameraRay<Scalar>)? {
    // t times a power of two: exact, and within range, as the world's
    // lengths are.
    var nearest = hit.map { $0.t * lengthScale } ?? .infinity
    var found: (Int, (t: Scalar, what: Nearest), CameraRay<Scalar>)?
    for (index, layer) in layers.enumerated() {
      let layerRay = CameraRay(
        origin: layer.rayOrigin, direction: ray.direction)
      guard let layerHit = layer.nearest(layerRay) else { continue }
      let world = layerHit.t * layer.lengthScale
      if world < nearest {
        nearest = world
        found = (index, layerHit, layerRay)
      }
    }
    return found
  }
}
