import Geometry

/// A list of objects hit as one (the course's `Group`).
public struct Group: Hittable {
  public var objects: [any Hittable]

  public init(_ objects: [any Hittable] = []) {
    self.objects = objects
  }

  /// The nearest hit of all the objects: each is asked only for a hit
  /// before the nearest so far, so a tie goes to the object listed first.
  public func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    // BEGIN SOLUTION week 1: camera and planes — the nearest hit of the
    //   objects in (tMin, tMax), each asked for a hit before the nearest so
    //   far (a tie goes to the object listed first)
    var nearest: Hit<Double>?
    for index in objects.indices {
      // By index, the limit first: the object is then asked where it lies
      // in the list (`for object in objects` would copy it out, counting a
      // reference that every thread's rays share).
      let limit = nearest?.t ?? tMax
      if let hit = objects[index].intersect(ray, after: tMin, before: limit) {
        nearest = hit
      }
    }
    return nearest
    // END SOLUTION
  }

  /// The union of the objects' boxes; nil when one has no bound.
  public var boundingBox: BoundingBox? {
    var box: BoundingBox?
    for object in objects {
      guard let next = object.boundingBox else { return nil }
      box = box?.union(next) ?? next
    }
    return box
  }
}
