/// A triangulated OBJ mesh, in the file's Double precision.
public struct OBJMesh: Hashable, Sendable {
  /// The `v` lines in order; x, y and z only.
  public var vertices: [Vector3<Double>]
  /// The `vn` lines in order, as written (not normalised; may be zero).
  public var normals: [Vector3<Double>]
  /// The `vt` lines in order, (u, v); a missing v is 0, w is dropped.
  public var textureCoordinates: [TextureCoordinate<Double>]
  /// The faces, fanned into triangles, in file order.
  public var triangles: [OBJTriangle]

  public init(
    vertices: [Vector3<Double>] = [], normals: [Vector3<Double>] = [],
    textureCoordinates: [TextureCoordinate<Double>] = [],
    triangles: [OBJTriangle] = []
  ) {
    self.vertices = vertices
    self.normals = normals
    self.textureCoordinates = textureCoordinates
    self.triangles = triangles
  }

  /// Whether any face gives texture coordinates.
  public var hasTextureCoordinates: Bool {
    triangles.contains { $0.textureIndices != nil }
  }

  /// The mesh with a normal per vertex where it has none (no `vn` lines),
  /// by the style's rule (see `MeshNormals`); vertices are taken by index,
  /// coincident positions are not merged. Faces whose cross product is zero
  /// or not finite add nothing; a vertex whose sum is zero gets the zero
  /// normal, for which a hit falls back to the face's own normal.
  public func smoothed(_ rule: MeshNormals = .unitMean) -> OBJMesh {
    guard let normals = smoothedNormals(rule) else { return self }
    var result = self
    result.normals = normals
    result.triangles = triangles.map {
      var face = $0
      face.normalIndices = $0.vertexIndices
      return face
    }
    return result
  }

  /// The normal per vertex of `smoothed`, or nil when `smoothed` leaves
  /// the mesh as it is (it has `vn` lines, or no faces).
  func smoothedNormals(_ rule: MeshNormals) -> [Vector3<Double>]? {
    guard normals.isEmpty, !triangles.isEmpty else { return nil }
    var sums = [Vector3<Double>](repeating: .zero, count: vertices.count)
    for face in triangles {
      let (a, b, c) = (
        Int(face.vertexIndices.x), Int(face.vertexIndices.y),
        Int(face.vertexIndices.z)
      )
      let cross = (vertices[b] - vertices[a]).cross(vertices[c] - vertices[a])
      guard cross.maxMagnitude > 0, cross.isFinite else { continue }
      let weighted = rule == .unitMean ? cross.normalized() : cross
      sums[a] += weighted
      sums[b] += weighted
      sums[c] += weighted
    }
    return sums.map {
      $0.maxMagnitude > 0 && $0.isFinite ? $0.normalized() : .zero
    }
  }

  /// The course loader's reading of `a/b` faces in a file that has both
  /// `vt` and `vn` lines, for a material without a texture: b is a normal
  /// index. Faces that give normals already are unchanged.
  ///
  /// - Returns: nil when some such b is not a valid normal index.
  public func readingTextureIndicesAsNormals() -> OBJMesh? {
    guard !normals.isEmpty else { return self }
    var result = self
    for index in result.triangles.indices {
      let face = result.triangles[index]
      guard face.normalIndices == nil, let second = face.textureIndices
      else { continue }
      guard second.max() < Int32(truncatingIfNeeded: normals.count) else {
        return nil
      }
      result.triangles[index].normalIndices = second
      result.triangles[index].textureIndices = nil
    }
    return result
  }

  /// The mesh as model triangles in precision S, with vertex normals and
  /// texture coordinates where the face gave them. Degenerate triangles (a
  /// repeated vertex, a zero-area face) are kept: they are never hit, and
  /// dropping them is the compiled scene's choice.
  public func makeTriangles<S: RayScalar>(
    materialIndex: Int, as _: S.Type = S.self
  ) -> [Triangle<S>] {
    triangles.indices.map {
      triangle(at: $0, materialIndex: materialIndex, as: S.self)
    }
  }

  /// The model triangle of `triangles[index]`, as `makeTriangles` makes
  /// it, for callers that store each one straight into their own array.
  ///
  /// - Precondition: `triangles.indices.contains(index)`.
  public func triangle<S: RayScalar>(
    at index: Int, materialIndex: Int, as _: S.Type = S.self
  ) -> Triangle<S> {
    let face = triangles[index]
    let v = face.vertexIndices
    let normals = face.normalIndices.map { n in
      Triangle<S>.VertexNormals(
        Vector3<S>(self.normals[Int(n.x)]),
        Vector3<S>(self.normals[Int(n.y)]),
        Vector3<S>(self.normals[Int(n.z)]))
    }
    let coordinates = face.textureIndices.map { t in
      Triangle<S>.TextureCoordinates(
        TextureCoordinate<S>(textureCoordinates[Int(t.x)]),
        TextureCoordinate<S>(textureCoordinates[Int(t.y)]),
        TextureCoordinate<S>(textureCoordinates[Int(t.z)]))
    }
    return Triangle<S>(
      Vector3<S>(vertices[Int(v.x)]), Vector3<S>(vertices[Int(v.y)]),
      Vector3<S>(vertices[Int(v.z)]), vertexNormals: normals,
      textureCoordinates: coordinates, materialIndex: materialIndex)
  }
}

/// One triangle of an OBJ mesh: 0-based indices into `OBJMesh.vertices`
/// and, when its face gave them, into `OBJMesh.normals` and
/// `OBJMesh.textureCoordinates`. Int32 indices keep a triangle at 48 bytes.
public struct OBJTriangle: Hashable, Sendable {
  public var vertexIndices: SIMD3<Int32>
  /// −1s when the face gave no normals; read through `normalIndices`.
  @usableFromInline var normalStorage: SIMD3<Int32>
  /// −1s when the face gave no texture coordinates.
  @usableFromInline var textureStorage: SIMD3<Int32>

  public init(
    vertexIndices: SIMD3<Int32>, normalIndices: SIMD3<Int32>? = nil,
    textureIndices: SIMD3<Int32>? = nil
  ) {
    self.vertexIndices = vertexIndices
    normalStorage = normalIndices ?? SIMD3(repeating: -1)
    textureStorage = textureIndices ?? SIMD3(repeating: -1)
  }

  /// Indices into `OBJMesh.normals`, or nil for a face without normals.
  @inlinable
  public var normalIndices: SIMD3<Int32>? {
    get { normalStorage.x < 0 ? nil : normalStorage }
    set { normalStorage = newValue ?? SIMD3(repeating: -1) }
  }

  /// Indices into `OBJMesh.textureCoordinates`, or nil.
  @inlinable
  public var textureIndices: SIMD3<Int32>? {
    get { textureStorage.x < 0 ? nil : textureStorage }
    set { textureStorage = newValue ?? SIMD3(repeating: -1) }
  }
}
