import Geometry

/// A group of many objects hit through a hierarchy of their boxes built
/// once (`BoxHierarchy`), as a mesh's triangles are; the readers' groups
/// of more than `threshold` objects become one (`SceneObjects`). It finds
/// what `Group`'s loop over the list finds, a tie still going to the
/// object listed first. Objects without a box (planes) are asked in turn.
struct BoxedGroup: Hittable {
  static let threshold = 16
  let objects: [any Hittable]
  private let bounded: [Int]
  private let unbounded: [Int]
  private let hierarchy: BoxHierarchy

  init(_ objects: [any Hittable]) {
    self.objects = objects
    let boxes = objects.map(\.boundingBox)
    bounded = boxes.indices.filter { boxes[$0] != nil }
    unbounded = boxes.indices.filter { boxes[$0] == nil }
    hierarchy = BoxHierarchy(boxes: bounded.compactMap { boxes[$0] })
  }

  func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    var nearest: (hit: Hit<Double>, index: Int)?
    func offer(_ index: Int) {
      // An object listed before the nearest may tie with it, and wins.
      let limit =
        nearest.map { index < $0.index ? $0.hit.t.nextUp : $0.hit.t } ?? tMax
      if let hit = objects[index].intersect(ray, after: tMin, before: limit) {
        nearest = (hit, index)
      }
    }
    unbounded.forEach(offer)
    hierarchy.forEachCandidate(ray, before: { nearest?.hit.t.nextUp ?? tMax })
    { offer(bounded[$0]) }
    return nearest?.hit
  }

  var boundingBox: BoundingBox? { unbounded.isEmpty ? hierarchy.bounds : nil }
}
