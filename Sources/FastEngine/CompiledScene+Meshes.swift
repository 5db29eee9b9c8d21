import FastKernels
import ExactArithmetic
import Geometry
import SceneDescription
import PlatformSupport

/// The scene's triangles compiled into records, mesh by mesh, straight from
/// the model's indexed storage (`TriangleMesh`): each shared vertex is put
/// into the kernel's frame once, each shared normal into the render's
/// precision once, and a triangle's record is built from its indices. No
/// array of model triangles is made on the way.
///
/// A large mesh is compiled in consecutive parts, one per thread, each
/// writing its records where they would be if no triangle were left out
/// (degenerate or large ones), then joined in order: the records, their
/// order and every table beside them are those of a compile on one thread.
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
    var large: [LargeTriangle] = []
    // The tables beside the records that grow to a triangle each (face
    // numbers, exact-plane indices) get their room once when needed:
    // grown by doubling after every record is written, each old copy
    // stood for a moment beside the full records.
    triangleSources.expect(list.count)
    for mesh in list.parts {
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
      let firstFace = triangleSources.face(0)
      let parts = Parallel.parts(
        mesh.count, threads: threads, from: 1 << 14, minimum: 1 << 13)
      // The vertices in the kernel's frame live as long as the compile of
      // the parts: freed before the join, whose tables take their place.
      let compiled = MeshCompile(
        mesh: mesh,
        framed: Self.map(mesh.vertices, threads: threads) {
          Self.frame($0, eye: eye, cameraRelative: cameraRelative)
        },
        eye: eye, cameraRelative: cameraRelative, firstFace: firstFace,
        textured: !textures.isEmpty
      ).run(parts: parts)
      append(
        compiled, firstFace: firstFace, triangles: list.count, large: &large)
    }
    return large
  }

  /// Appends one mesh's compiled parts, in order: records and texture
  /// coordinates, face numbers, exact planes and large triangles, of a
  /// list of `triangles` in all.
  private mutating func append(
    _ compiled: MeshCompile.Output, firstFace: Int, triangles total: Int,
    large: inout [LargeTriangle]
  ) {
    let base = triangles.count
    if base == 0 {
      triangles = compiled.records
    } else {
      triangles += compiled.records
    }
    if !textures.isEmpty {
      triangleTextureCoordinates += compiled.textureCoordinates
    }
    var ordinal = base
    for part in compiled.parts {
      triangleSources.append(
        faces: firstFace + part.faces.lowerBound..<firstFace
          + part.faces.upperBound,
        leavingOut: part.leftOut.map { firstFace + $0 })
      // One entry per ordinary triangle from the first that needs a plane.
      if !part.exact.isEmpty || !exactPlaneIndices.isEmpty {
        if exactPlaneIndices.isEmpty {
          exactPlaneIndices.reserveCapacity(total)
          exactPlaneIndices += repeatElement(-1, count: ordinal)
        }
        exactPlaneIndices += repeatElement(-1, count: part.count)
        for (offset, plane) in part.exact {
          exactPlaneIndices[ordinal + offset] = Int32(
            truncatingIfNeeded: exactPlanes.count)
          exactPlanes.append(plane)
        }
      }
      ordinal += part.count
      large += part.large
    }
  }

  /// One mesh's triangles compiled in parts on threads of their own.
  private struct MeshCompile {
    let mesh: TriangleMesh<Double>
    /// The mesh's vertices in the kernel's frame.
    let framed: [Vector3<Scalar>]
    let eye: Vector3<Double>
    let cameraRelative: Bool
    /// The face number of the mesh's first face (`TriangleSources`).
    let firstFace: Int
    let textured: Bool

    /// What one part of the mesh's faces compiled to.
    struct Part {
      /// Its faces, in the mesh's numbering.
      var faces: Range<Int> = 0..<0
      /// Ordinary triangles written, from the part's first face's place.
      var count = 0
      /// The faces of `faces` that are not among them, in order: degenerate
      /// and large ones.
      var leftOut: [Int] = []
      /// Per ordinary triangle that needs one, its offset among the part's
      /// and its exact plane (`TrianglePlane.needsExactT`).
      var exact: [(Int, TrianglePlane.Exact<Scalar>)] = []
      var large: [LargeTriangle] = []
    }

    struct Output {
      var records: [TriangleRecord<Scalar>]
      var textureCoordinates: [Triangle<Scalar>.TextureCoordinates?]
      var parts: [Part]
    }

    /// The mesh compiled in `parts` parts, each writing from its first
    /// face's place; the records of later parts are then moved down over
    /// the places of faces left out before them.
    func run(parts: Int) -> Output {
      let count = mesh.count
      // On ordinary pages: 2 MiB pages cost more to fault in once memory
      // is fragmented (docs/PERFORMANCE.md, "Large meshes").
      var results = [Part](repeating: Part(), count: parts)
      var coordinates: [Triangle<Scalar>.TextureCoordinates?] = []
      var written = 0
      let records = [TriangleRecord<Scalar>](
        unsafeUninitializedCapacity: count
      ) { records, initialized in
        coordinates = .init(unsafeUninitializedCapacity: textured ? count : 0) {
          coordinates, initializedCoordinates in
          results.withUnsafeMutableBufferPointer { results in
            Parallel.inParts(count, parts) { part, range in
              results[part] = compile(
                range, into: records.baseAddress!,
                coordinates: textured ? coordinates.baseAddress : nil)
            }
            for part in results {
              let from = part.faces.lowerBound
              if from != written {
                (records.baseAddress! + written).moveInitialize(
                  from: records.baseAddress! + from, count: part.count)
                if textured {
                  (coordinates.baseAddress! + written).moveInitialize(
                    from: coordinates.baseAddress! + from, count: part.count)
                }
              }
              written += part.count
            }
          }
          initializedCoordinates = textured ? written : 0
        }
        initialized = written
      }
      return Output(
        records: records, textureCoordinates: coordinates, parts: results)
    }

    /// Compiles the faces `range`, writing ordinary triangles' records
    /// (and texture coordinates) from `records + range.lowerBound` on.
    private func compile(
      _ range: Range<Int>,
      into records: UnsafeMutablePointer<TriangleRecord<Scalar>>,
      coordinates: UnsafeMutablePointer<Triangle<Scalar>.TextureCoordinates?>?
    ) -> Part {
      var part = Part(faces: range)
      for index in range {
        let (a, b, c) = mesh.corners(index)
        let record = TriangleRecord(v0: framed[a], v1: framed[b], v2: framed[c])
        // A degenerate triangle is never hit: leaving it out changes nothing.
        guard let normal = record.geometricNormal else {
          part.leftOut.append(index)
          continue
        }
        let textureCoordinates = textured ? self.textureCoordinates(index) : nil
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
          let shading = TriangleShading<Scalar>(
            face: firstFace + index, textureCoordinates: textureCoordinates)
          part.large.append(
            (record, shading, LargeTrianglePlane(exact, relative: relative)))
          part.leftOut.append(index)
          continue
        }
        let place = range.lowerBound + part.count
        (records + place).initialize(to: record)
        if let coordinates {
          (coordinates + place).initialize(to: textureCoordinates)
        }
        if cameraRelative, TrianglePlane.needsExactT(relative: relative),
          let plane = TrianglePlane.exact(
            vertices.0, vertices.1, vertices.2, origin: eye, as: Scalar.self)
        {
          part.exact.append((part.count, plane))
        }
        part.count += 1
      }
      return part
    }

    /// Face `index`'s texture coordinates, or nil when it has none.
    private func textureCoordinates(_ index: Int)
      -> Triangle<Scalar>.TextureCoordinates?
    {
      mesh.textureCorners(index).map {
        Triangle<Scalar>.TextureCoordinates(
          TextureCoordinate(mesh.textureCoordinates[$0.0]),
          TextureCoordinate(mesh.textureCoordinates[$0.1]),
          TextureCoordinate(mesh.textureCoordinates[$0.2]))
      }
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
