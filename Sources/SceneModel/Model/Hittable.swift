/// Anything a ray can hit, as the course's loop asks it: the hit protocol
/// of the course (its `Hitable`).
///
/// The course's shapes conform to it (`Sources/Course`), and the course
/// engine renders by asking every object of the scene for its nearest hit.
/// A shape of your own that conforms to it renders in both engines: the
/// fast engine tests any object it does not specialise through this
/// protocol, behind the object's `boundingBox` (docs/ADDING-A-SHAPE.md).
///
/// Rays and hits are in Double, the precision of the scene as read.
public protocol Hittable: Sendable {
  /// The nearest hit with tMin < t < tMax, or nil.
  ///
  /// t is in multiples of the ray's direction (which need not be unit
  /// length); the hit's normal is unit length.
  func intersect(_ ray: Ray<Double>, after tMin: Double, before tMax: Double)
    -> Hit<Double>?

  /// A box that holds every point where the object can be hit, or nil when
  /// it has no bound (a plane).
  var boundingBox: BoundingBox? { get }
}

/// An object of a kind that neither reader nor fast engine specialises,
/// held in a scene by its hit protocol (`SceneObject.shape`).
///
/// Two are equal when they are the same object: a `Hittable` need not be
/// comparable.
public struct Shape: Hashable, Sendable {
  public let object: any Hittable
  private let identity: Identity

  private final class Identity: Sendable {}

  public init(_ object: any Hittable) {
    self.object = object
    identity = Identity()
  }

  public static func == (a: Shape, b: Shape) -> Bool {
    a.identity === b.identity
  }

  public func hash(into hasher: inout Hasher) {
    hasher.combine(ObjectIdentifier(identity))
  }
}

/// A shape placed in the world by an affine matrix M (its points P appear
/// at M·P), hit the course's way: the ray taken into the shape's space by
/// M⁻¹, its direction not renormalised so that t means the same point in
/// both spaces, and the normal brought back by the inverse transpose.
public struct PlacedShape: Hittable {
  public var shape: any Hittable
  public var matrix: Matrix4<Double>
  public var inverse: Matrix4<Double>

  public init(
    _ shape: any Hittable, matrix: Matrix4<Double>, inverse: Matrix4<Double>
  ) {
    self.shape = shape
    self.matrix = matrix
    self.inverse = inverse
  }

  public func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    let local = Ray(
      origin: inverse.transformPoint(ray.origin),
      direction: inverse.transformDirection(ray.direction))
    guard var hit = shape.intersect(local, after: tMin, before: tMax) else {
      return nil
    }
    hit.normal = matrix.transformNormal(hit.normal)
    return hit
  }

  public var boundingBox: BoundingBox? {
    shape.boundingBox?.transformed(by: matrix)
  }
}
