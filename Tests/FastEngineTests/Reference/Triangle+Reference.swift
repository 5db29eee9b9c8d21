@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

// What the tests ask of a described triangle beyond what the file said:
// whether it has an area, and the normal the reference shades with. Not in
// SceneDescription: the description is plain data, and each engine has its
// own rule in its own model.
extension Triangle {
  /// Whether the triangle has no area as computed: a repeated vertex,
  /// collinear vertices (to rounding of the cross product), or a
  /// non-finite coordinate. Degenerate triangles are never hit, so a
  /// compiled scene may drop them.
  var isDegenerate: Bool { geometricNormal == nil }

  /// The shading normal at barycentrics (u, v, w): the interpolated vertex
  /// normal when there are vertex normals and it is not zero (opposed
  /// normals can cancel), otherwise `geometric`.
  func shadingNormal(
    u: Scalar, v: Scalar, w: Scalar, geometric: Vector3<Scalar>
  ) -> Vector3<Scalar> {
    guard let normals = vertexNormals else { return geometric }
    let blended = normals.n0 * u + normals.n1 * v + normals.n2 * w
    guard blended.maxMagnitude > 0, blended.isFinite else { return geometric }
    return blended.normalized()
  }
}
