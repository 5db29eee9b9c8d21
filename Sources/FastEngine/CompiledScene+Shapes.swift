import FastKernels
import Geometry
import SceneDescription

/// Shapes of kinds the fast engine does not specialise (`SceneObject.shape`,
/// docs/ADDING-A-SHAPE.md): tested after its own kinds, through each
/// shape's `Hittable.intersect`, in Double and in the world's units.
extension CompiledScene {
  /// Keeps the shapes, bounded ones first in scene order, then those
  /// without a bound (a plane of one's own); a hierarchy over the bounded
  /// ones' boxes, in the world's units, once there are two of them.
  mutating func placeShapes(_ placed: [PlacedShape]) {
    let all = placed.map { WorldShape($0) }
    let boxes = all.map(\.boundingBox)
    let bounded = all.indices.filter { boxes[$0] != nil }
    let unbounded = all.indices.filter { boxes[$0] == nil }
    shapes = (bounded + unbounded).map { all[$0] }
    shapeBoxes = (bounded + unbounded).map { boxes[$0] }
    boundedShapeCount = bounded.count
    guard bounded.count >= 2 else { return }
    let bvh = shapeBoxes.withUnsafeBufferPointer { boxes in
      BoundingVolumeHierarchy<Double>(
        count: bounded.count, threads: threads
      ) {
        let box = boxes[$0]!
        return (box.lower, box.upper)
      }
    }
    bvh.arrange(&shapes)
    bvh.arrange(&shapeBoxes)
    shapeHierarchy = bvh
  }

  /// Offers the shapes' hits to `nearest`, each asked, in Double and in
  /// the world's units, for a hit before the best so far: the bounded
  /// ones through their hierarchy (or their box, for a single one), then
  /// those without a bound in order.
  func testShapes(
    _ ray: CameraRay<Scalar>, _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    let world = shapeRay(ray)
    let scale = Double(lengthScale)
    var first = 0
    if let shapeHierarchy {
      let found = shapeHierarchy.nearest(
        CameraRay(origin: world.origin, direction: world.direction),
        before: Double(nearest.t) * scale,
        leaves: ShapeLeaves(shapes: shapes, ray: world))
      if let found {
        nearest.test(.shape(found.index)) { before in
          let t = Scalar(found.t / scale)
          return t > 0 && t < before ? t : nil
        }
      }
      first = boundedShapeCount
    }
    let reciprocal = Vector3(
      1 / world.direction.x, 1 / world.direction.y, 1 / world.direction.z)
    for index in first..<shapes.count {
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

/// The shapes in a hierarchy's leaves, as one world ray tests them.
struct ShapeLeaves: LeafPrimitives {
  let shapes: [WorldShape]
  let ray: Ray<Double>

  func intersect(_ position: Int, before tMax: Double) -> Double? {
    shapes[position].intersect(ray, after: 0, before: tMax)?.t
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
