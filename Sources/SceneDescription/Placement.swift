import Geometry

/// Where the transforms around an object put it: M, which places the
/// object's points P at M·P, and M⁻¹.
@usableFromInline
package typealias Placement<Scalar: RayScalar> = (
  matrix: Matrix4<Scalar>, inverse: Matrix4<Scalar>
)

extension Group {
  /// The one walk over a scene: calls `body` with every object of the
  /// group that is neither a group nor a transform, in file order, and the
  /// placement of the transforms around it (nil under none), theirs
  /// multiplied outermost first. What handles the scene kind by kind (the
  /// compiled engine's flattening, the readers' checks) goes through it, so
  /// that a new kind of object reaches each by its own `switch`
  /// (docs/ADDING-A-SHAPE.md).
  @inlinable
  package func forEachPlaced(
    under placement: Placement<Scalar>? = nil,
    _ body: (SceneObject<Scalar>, Placement<Scalar>?) -> Void
  ) {
    for object in objects { object.forEachPlaced(under: placement, body) }
  }
}

extension SceneObject {
  /// `Group.forEachPlaced` for this one entry under `placement`.
  @inlinable
  package func forEachPlaced(
    under placement: Placement<Scalar>?,
    _ body: (SceneObject<Scalar>, Placement<Scalar>?) -> Void
  ) {
    switch self {
    case .group(let group):
      group.forEachPlaced(under: placement, body)
    case .transform(let inner):
      let combined =
        placement.map {
          ($0.matrix * inner.matrix, inner.inverse * $0.inverse)
        } ?? (inner.matrix, inner.inverse)
      inner.object.forEachPlaced(under: combined, body)
    case .sphere, .plane, .triangle, .mesh, .shape:
      body(self, placement)
    }
  }

  /// Which kind of entry this is.
  package var kind: SceneObjectKind {
    switch self {
    case .sphere: .sphere
    case .plane: .plane
    case .triangle: .triangle
    case .mesh: .mesh
    case .group: .group
    case .transform: .transform
    case .shape: .shape
    }
  }

  /// The kind's name as the text format writes it.
  package var kindName: String { kind.name }
}

/// The kinds of entry a group holds (`SceneObject`), listed: what a test
/// that must meet every kind walks, so that a new kind joins it.
package enum SceneObjectKind: CaseIterable, Sendable {
  case sphere, plane, triangle, mesh, group, transform, shape

  /// The name the text format writes it by.
  package var name: String {
    switch self {
    case .sphere: "Sphere"
    case .plane: "Plane"
    case .triangle: "Triangle"
    case .mesh: "TriangleMesh"
    case .group: "Group"
    case .transform: "Transform"
    case .shape: "a shape of its own"
    }
  }
}

extension Sphere {
  /// The sphere `matrix` places, where it is a sphere: under a similarity
  /// (`Matrix4.similarityScale`), its centre moved and its radius scaled;
  /// nil under any other matrix, which makes it an ellipsoid.
  @inlinable
  package func placed(by matrix: Matrix4<Scalar>) -> Sphere? {
    guard let scale = matrix.similarityScale else { return nil }
    return Sphere(
      center: matrix.transformPoint(center), radius: radius * scale,
      materialIndex: materialIndex)
  }
}

extension Plane {
  /// The plane `matrix` places: its normal by the inverse transpose, its
  /// offset from the moved point nearest the origin.
  @inlinable
  package func placed(by matrix: Matrix4<Scalar>) -> Plane {
    let normal = matrix.transformNormal(self.normal)
    let point = matrix.transformPoint(self.normal * offset)
    return Plane(
      normal: normal, offset: normal.dot(point),
      materialIndex: materialIndex)
  }
}

extension Triangle {
  /// The triangle placed by `matrix`: its vertices moved, its vertex
  /// normals by the inverse transpose.
  package func moved(by matrix: Matrix4<Scalar>) -> Triangle {
    var moved = self
    moved.v0 = matrix.transformPoint(v0)
    moved.v1 = matrix.transformPoint(v1)
    moved.v2 = matrix.transformPoint(v2)
    if let normals = vertexNormals {
      // Not normalised one by one: the hit's interpolation then gives
      // the transform of the object's interpolated normal.
      // A scale far from 1 (`UniformScale 1e20`) would take the
      // cofactors, its square, out of range: they are taken of the
      // matrix rescaled by a power of two, the same directions.
      let normalMatrix = matrix.withLinearPartNearOne()
      moved.vertexNormals = Triangle.VertexNormals(
        normalMatrix.cofactorNormal(normals.n0),
        normalMatrix.cofactorNormal(normals.n1),
        normalMatrix.cofactorNormal(normals.n2))
    }
    return moved
  }
}


extension TriangleMesh {
  /// The mesh placed by `matrix`, as `Triangle.moved(by:)` places each of
  /// its triangles: every vertex moved, every normal by the cofactors of
  /// the matrix rescaled near 1. Each shared value is moved once, by the
  /// same operations, so each triangle is the one `moved` gives.
  package func moved(by matrix: Matrix4<Scalar>) -> TriangleMesh {
    var moved = self
    moved.storage = StorageTag()
    moved.vertices = vertices.map { matrix.transformPoint($0) }
    if normalsFollowVertices || !normalIndices.isEmpty {
      let normalMatrix = matrix.withLinearPartNearOne()
      moved.normals = normals.map { normalMatrix.cofactorNormal($0) }
    }
    return moved
  }
}

extension Group {
  /// How many spheres, planes, triangles and ellipsoids (spheres a
  /// placement stretches) the group holds where its transforms put them,
  /// as a render counts them; shapes of one's own are not counted.
  package var primitiveCounts:
    (spheres: Int, planes: Int, triangles: Int, ellipsoids: Int)
  {
    var counts = (spheres: 0, planes: 0, triangles: 0, ellipsoids: 0)
    forEachPlaced { object, placement in
      switch object {
      case .sphere:
        if let placement, placement.matrix.similarityScale == nil {
          counts.ellipsoids += 1
        } else {
          counts.spheres += 1
        }
      case .plane: counts.planes += 1
      case .triangle: counts.triangles += 1
      case .mesh(let mesh): counts.triangles += mesh.count
      case .shape, .group, .transform: break
      }
    }
    return counts
  }
}
