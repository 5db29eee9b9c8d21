import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// The scene's triangles compiled into records, mesh by mesh, straight from
/// the model's indexed storage (`TriangleMesh`): each shared vertex is put
/// into the kernel's frame once, each shared normal into the render's
/// precision once, and a triangle's record is built from its indices. No
/// array of model triangles is made on the way.
extension CompiledScene {
  /// Appends the ordinary triangles of `list`, in order, degenerate ones
  /// left out, and returns the large ones (`TrianglePlane`) for
  /// `appendLargeTriangles`. Each record and its shading hold the values
  /// compiling the list's triangles one by one gave: the same functions of
  /// the same model values.
  mutating func compileTriangles(
    _ list: TriangleList<Double>, eye: Vector3<Double>
  ) -> [LargeTriangle] {
    let cameraRelative = Kernel.frameOrigin(eye: eye) == .zero
    // On ordinary pages: 2 MiB pages cost more to fault in once memory is
    // fragmented (docs/PERFORMANCE.md, "Large meshes").
    triangles.reserveCapacity(list.count)
    var large: [LargeTriangle] = []
    for mesh in list.parts {
      let framed = Self.map(mesh.vertices) {
        Self.frame($0, eye: eye, cameraRelative: cameraRelative)
      }
      let normalBase = vertexNormals.count
      triangleSources.add(mesh, normalBase: normalBase)
      if mesh.normalsFollowVertices || !mesh.normalIndices.isEmpty {
        if vertexNormals.isEmpty, Scalar.self == Double.self {
          // A Double render's normals are the model's: shared, not copied
          // (a cast, `as?`, copied them element by element). The types are
          // the same, so the cast of the array is the array itself.
          vertexNormals = unsafeBitCast(
            mesh.normals, to: [Vector3<Scalar>].self)
        } else {
          vertexNormals += mesh.normals.map { Vector3<Scalar>($0) }
        }
      }
      for index in mesh.indices {
        let (a, b, c) = mesh.corners(index)
        let record = TriangleRecord(v0: framed[a], v1: framed[b], v2: framed[c])
        // A degenerate triangle is never hit: leaving it out changes nothing.
        guard let normal = record.geometricNormal else { continue }
        let shading = TriangleShading<Scalar>(
          face: triangleSources.face(index),
          textureCoordinates: textures.isEmpty
            ? nil
            : mesh.textureCorners(index).map {
              Triangle<Scalar>.TextureCoordinates(
                TextureCoordinate(mesh.textureCoordinates[$0.0]),
                TextureCoordinate(mesh.textureCoordinates[$0.1]),
                TextureCoordinate(mesh.textureCoordinates[$0.2]))
            })
        let relative = (record.v0, record.v1, record.v2)
        let vertices = (mesh.vertices[a], mesh.vertices[b], mesh.vertices[c])
        if cameraRelative,
          let plane = TrianglePlane.make(
            relative: relative, normal: normal, v0: vertices.0, origin: eye)
        {
          let exact =
            TrianglePlane.exact(
              vertices.0, vertices.1, vertices.2, origin: eye, as: Scalar.self)
            ?? TrianglePlane.Exact(
              normal: plane.normal, normalTail: .zero,
              distance: plane.distance,
              isAxisAligned: PlaneIntersection.isAxisAligned(plane.normal))
          large.append(
            (record, shading, LargeTrianglePlane(exact, relative: relative)))
          continue
        }
        appendTriangle(record, shading)
        if cameraRelative {
          appendExactPlane(relative: relative, vertices: vertices, eye: eye)
        }
      }
    }
    return large
  }

  /// Records the exact plane of the triangle just appended when its
  /// watertight t would lose digits (`TrianglePlane.needsExactT`), else
  /// −1 once some earlier triangle has one.
  mutating func appendExactPlane(
    relative: (Vector3<Scalar>, Vector3<Scalar>, Vector3<Scalar>),
    vertices: (Vector3<Double>, Vector3<Double>, Vector3<Double>),
    eye: Vector3<Double>
  ) {
    if TrianglePlane.needsExactT(relative: relative),
      let plane = TrianglePlane.exact(
        vertices.0, vertices.1, vertices.2, origin: eye, as: Scalar.self)
    {
      if exactPlaneIndices.isEmpty {
        exactPlaneIndices = Array(repeating: -1, count: triangles.count - 1)
      }
      exactPlaneIndices.append(Int32(truncatingIfNeeded: exactPlanes.count))
      exactPlanes.append(plane)
    } else if !exactPlaneIndices.isEmpty {
      exactPlaneIndices.append(-1)
    }
  }

  /// `point` in the kernel's frame: relative to the eye, compensated and
  /// rounded once (`CameraRelative`), when the kernel's rays start at the
  /// origin; else as it is, rounded to the render's precision.
  static func frame(
    _ point: Vector3<Double>, eye: Vector3<Double>, cameraRelative: Bool
  ) -> Vector3<Scalar> {
    guard cameraRelative else { return Vector3(point) }
    func component(_ a: Double, _ b: Double) -> Scalar {
      let difference = Compensated.twoSum(a, -b)
      return CameraRelative.narrowed(difference.sum, difference.error)
    }
    return Vector3(
      component(point.x, eye.x), component(point.y, eye.y),
      component(point.z, eye.z))
  }
}
