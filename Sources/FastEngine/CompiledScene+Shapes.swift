import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// Shapes of kinds the fast engine does not specialise (`SceneObject.shape`,
/// docs/ADDING-A-SHAPE.md): tested after its own kinds, through each
/// shape's `Hittable.intersect`, in Double and in the world's units.
extension CompiledScene {
  /// Offers the hits of the other shapes to `nearest`, in order: each is
  /// asked, in Double and in the world's units, for a hit strictly before
  /// the best so far, when the ray meets its box.
  func testShapes(
    _ ray: CameraRay<Scalar>, _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    let world = shapeRay(ray)
    let reciprocal = Vector3(
      1 / world.direction.x, 1 / world.direction.y, 1 / world.direction.z)
    let scale = Double(lengthScale)
    for index in shapes.indices {
      nearest.test(.shape(index)) { before in
        let tMax = Double(before) * scale
        if let box = shapeBoxes[index],
          !box.isHit(by: world, reciprocal: reciprocal, after: 0, before: tMax)
        {
          return nil
        }
        guard
          let hit = shapes[index].intersect(world, after: 0, before: tMax)
        else { return nil }
        let t = Scalar(hit.t / scale)
        return t > 0 && t < before ? t : nil
      }
    }
  }

  /// A camera ray as the shapes see it: from the eye in the world.
  func shapeRay(_ ray: CameraRay<Scalar>) -> Ray<Double> {
    Ray(origin: shapeEye, direction: Vector3<Double>(ray.direction))
  }

  /// The hit of shape `index` found by `testShapes`: its nearest.
  func shapeHit(_ index: Int, _ ray: CameraRay<Scalar>) -> Hit<Double>? {
    shapes[index].intersect(shapeRay(ray), after: 0, before: .infinity)
  }
}

/// A shape of one's own in the world: hit the course's way when a
/// transform places it, the ray taken into the shape's space by M⁻¹ (its
/// direction not renormalised, so that t means the same point in both
/// spaces) and the normal brought back by the inverse transpose.
struct WorldShape: Hittable {
  let placed: PlacedShape

  init(_ placed: PlacedShape) {
    self.placed = placed
  }

  func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    guard let (matrix, inverse) = placed.placement else {
      return placed.shape.intersect(ray, after: tMin, before: tMax)
    }
    let local = Ray(
      origin: inverse.transformPoint(ray.origin),
      direction: inverse.transformDirection(ray.direction))
    guard var hit = placed.shape.intersect(local, after: tMin, before: tMax)
    else { return nil }
    hit.normal = matrix.transformNormal(hit.normal)
    return hit
  }

  var boundingBox: BoundingBox? {
    guard let (matrix, _) = placed.placement else {
      return placed.shape.boundingBox
    }
    return placed.shape.boundingBox?.transformed(by: matrix)
  }
}
