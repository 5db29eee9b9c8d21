/// Anything a ray can hit, as the course's loop asks it: the hit protocol
/// of the course (its `Hitable`).
///
/// The course's shapes conform to it (`Sources/Course`), and the course
/// engine renders by asking every object of the scene for its nearest hit.
/// A shape of your own that conforms to it renders in both engines: the
/// compiled engine tests any object it does not specialise through this
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

/// An object of a kind that neither reader nor compiled engine specialises,
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
