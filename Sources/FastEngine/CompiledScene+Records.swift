import FastKernels
import Geometry
import SceneDescription

/// A triangle as the loop tests it: vertices in the kernel's frame. Its
/// shading (material, vertex normals, texture coordinates) is kept beside
/// the records (`CompiledScene.triangleSources`), read once per
/// pixel rather than carried through every test.
struct TriangleRecord<Scalar: RayScalar>: Sendable {
  var v0: Vector3<Scalar>
  var v1: Vector3<Scalar>
  var v2: Vector3<Scalar>

  /// The winding's unit normal (`Triangle.geometricNormal`); nil for a
  /// degenerate triangle.
  var geometricNormal: Vector3<Scalar>? {
    Triangle(v0, v1, v2).geometricNormal
  }

  /// The barycentric weights of v0, v1, v2 where `ray` hits (the same
  /// computation as the hit's, so the same values), or nil on a miss.
  func barycentrics(
    of ray: CameraRay<Scalar>
  ) -> (u: Scalar, v: Scalar, w: Scalar)? {
    weights(WatertightRay(Ray(origin: ray.origin, direction: ray.direction)))
  }

  @inline(__always)
  func intersect(
    _ ray: WatertightRay<Scalar>, before tMax: Scalar
  ) -> (t: Scalar, u: Scalar, v: Scalar, w: Scalar)? {
    TriangleIntersection.intersect(ray, v0, v1, v2, after: 0, before: tMax)
  }

  /// `intersect` with t from the triangle's exact plane
  /// (`TrianglePlane.Exact`): the same hits on the line, the same
  /// barycentrics.
  @inline(__always)
  func intersect(
    _ ray: WatertightRay<Scalar>, plane: TrianglePlane.Exact<Scalar>,
    before tMax: Scalar
  ) -> (t: Scalar, u: Scalar, v: Scalar, w: Scalar)? {
    TriangleIntersection.intersect(
      ray, PermutedTriangle(ray, v0, v1, v2), plane: plane, after: 0,
      before: tMax)
  }

  /// The barycentrics of the watertight test on the ray's whole line: a
  /// hit found in (0, t) has the same weights on the line, and a triangle
  /// whose t comes from its plane has them even where the watertight t,
  /// which it replaces, strayed below 0.
  @inline(__always)
  func weights(_ ray: WatertightRay<Scalar>)
    -> (u: Scalar, v: Scalar, w: Scalar)?
  {
    TriangleIntersection.intersect(
      ray, v0, v1, v2, after: -.infinity, before: .infinity
    ).map { ($0.u, $0.v, $0.w) }
  }

  /// The t of a triangle much larger than its distance from the eye, for
  /// the record at `record`, read in place: the watertight test decides
  /// the hit, the plane gives t (`TrianglePlane`). The plane first, which
  /// settles most misses (a ground triangle's sky) with one product and a
  /// division, then the watertight test, by its edges alone where they
  /// decide it (`LargeTrianglePlane.edgesDecide`). Both must hold, in
  /// either order, so the answer is the same.
  @inline(__always)
  static func t(
    _ ray: WatertightRay<Scalar>, _ record: UnsafePointer<TriangleRecord>,
    plane: LargeTrianglePlane<Scalar>, before tMax: Scalar
  ) -> Scalar? {
    guard
      let t = plane.plane.t(direction: ray.direction, after: 0, before: tMax)
    else { return nil }
    let (v0, v1, v2) = (
      record.pointee.v0, record.pointee.v1, record.pointee.v2
    )
    let covered =
      plane.edgesDecide
      ? TriangleIntersection.covers(ray, v0, v1, v2)
      : TriangleIntersection.intersect(
        ray, v0, v1, v2, after: -.infinity, before: .infinity) != nil
    return covered ? t : nil
  }

  /// The normal where `ray` hits, from the vertex normals `normals` (nil
  /// for flat shading): the barycentrics are found again (the same
  /// computation as the hit's, so the same values).
  func normal(
    of ray: CameraRay<Scalar>, normals: Triangle<Scalar>.VertexNormals?
  ) -> Vector3<Scalar> {
    // The geometric normal only where it is the answer: found again from
    // the vertices, it is not stored beside them.
    guard let normals else { return geometricNormal ?? .zero }
    guard let hit = barycentrics(of: ray) else {
      return geometricNormal ?? .zero
    }
    return normal(
      weights: TriangleWeights(u: hit.u, v: hit.v, w: hit.w), normals: normals)
  }

  /// The normal for a hit's barycentric weights (`intersect`'s u, v, w),
  /// interpolated from the vertex normals `normals`.
  func normal(
    weights: TriangleWeights<Scalar>,
    normals: Triangle<Scalar>.VertexNormals
  ) -> Vector3<Scalar> {
    let blended =
      normals.n0 * weights.u + normals.n1 * weights.v + normals.n2 * weights.w
    guard blended.maxMagnitude > 0, blended.isFinite else {
      return geometricNormal ?? .zero
    }
    return blended.normalized()
  }
}

/// The barycentric weights of v0, v1, v2 at a triangle's hit, as the
/// watertight test gives them (`TriangleRecord.intersect`): kept by the
/// screen tiles' search from the test that found the nearest hit, so that
/// the normal need not run the test again (the same values either way).
struct TriangleWeights<Scalar: RayScalar>: Sendable {
  var u: Scalar
  var v: Scalar
  var w: Scalar
}

/// Triangles tested against one prepared ray, for the hierarchy.
struct TriangleLeaves<Scalar: RayScalar>: LeafPrimitives {
  let records: UnsafeBufferPointer<TriangleRecord<Scalar>>
  let ray: WatertightRay<Scalar>

  @inline(__always)
  func intersect(_ position: Int, before tMax: Scalar) -> Scalar? {
    records[position].intersect(ray, before: tMax)?.t
  }
}

/// Triangles tested against one prepared ray, for the hierarchy of a scene
/// where some take t from their exact planes (`exactPlaneIndices`).
struct PlanedTriangleLeaves<Scalar: RayScalar>: LeafPrimitives {
  let records: UnsafeBufferPointer<TriangleRecord<Scalar>>
  let planeIndices: UnsafeBufferPointer<Int32>
  let planes: UnsafeBufferPointer<TrianglePlane.Exact<Scalar>>
  let ray: WatertightRay<Scalar>

  /// The plane's index is read only for rays that reach the triangle.
  @inline(__always)
  func intersect(_ position: Int, before tMax: Scalar) -> Scalar? {
    let record = records[position]
    return TriangleIntersection.intersect(
      ray, PermutedTriangle(ray, record.v0, record.v1, record.v2), after: 0,
      before: tMax
    ) {
      let plane = planeIndices[position]
      return plane >= 0 ? planes[Int(plane)] : nil
    }?.t
  }
}

/// Per compiled triangle, the indices of its vertex normals in
/// `CompiledScene.vertexNormals`, or −1s for flat shading.
struct TriangleNormalIndices: Sendable {
  var n0: Int32
  var n1: Int32
  var n2: Int32

  static var none: TriangleNormalIndices { .init(n0: -1, n1: -1, n2: -1) }
}

/// What shading reads of a compiled triangle besides its record.
struct TriangleShading<Scalar: RayScalar>: Sendable {
  /// The face it was compiled from (`TriangleSources`): its material and
  /// normals.
  var face: Int
  /// Only for textured renders.
  var textureCoordinates: Triangle<Scalar>.TextureCoordinates?
}

extension CompiledScene {
  /// Appends a compiled triangle with its material, normals and, for a
  /// textured render, its texture coordinates.
  mutating func appendTriangle(
    _ record: TriangleRecord<Scalar>, _ shading: TriangleShading<Scalar>
  ) {
    triangles.append(record)
    triangleSources.append(face: shading.face)
    if !textures.isEmpty {
      triangleTextureCoordinates.append(shading.textureCoordinates)
    }
  }

  /// The vertex normals of compiled triangle `index`, or nil.
  @inline(__always)
  func vertexNormals(ofTriangle index: Int) -> Triangle<Scalar>.VertexNormals? {
    let normals = triangleSources.normals(index)
    guard normals.n0 >= 0 else { return nil }
    return Triangle.VertexNormals(
      vertexNormals[Int(normals.n0)], vertexNormals[Int(normals.n1)],
      vertexNormals[Int(normals.n2)])
  }
}
