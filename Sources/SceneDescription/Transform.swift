import Geometry

/// An object placed by an affine matrix (the course's `Transform`): the
/// object's points P appear at M·P.
///
/// The course takes the ray into the object's space by M⁻¹ (direction not
/// renormalised, so t means the same point in both spaces) and brings the
/// normal back by the inverse transpose. Here the object is placed in the
/// world instead wherever it stays the same kind of object there, which
/// rounds less: triangles by their moved vertices, planes by their moved
/// normal and point, spheres under similarities by their moved centre and
/// scaled radius. Only a sphere stretched into an ellipsoid stays a
/// transformed sphere (`TransformedSphere`), hit in the frame of its axes
/// by the stable method, in its own space by the naive one. The fast
/// engine places objects the same way, once per render
/// (`Group.flattened`).
public struct Transform<Scalar: RayScalar>: Hashable, Sendable {
  public var matrix: Matrix4<Scalar>
  public var inverse: Matrix4<Scalar>
  public var object: SceneObject<Scalar>

  /// Nil when the matrix has no inverse (a scale of zero, say).
  public init?(matrix: Matrix4<Scalar>, object: SceneObject<Scalar>) {
    guard let inverse = matrix.inverse() else { return nil }
    self.init(matrix: matrix, inverse: inverse, object: object)
  }

  /// A transform whose inverse is known (a product of inverses, say).
  package init(
    matrix: Matrix4<Scalar>, inverse: Matrix4<Scalar>,
    object: SceneObject<Scalar>
  ) {
    self.matrix = matrix
    self.inverse = inverse
    self.object = object
  }
}
