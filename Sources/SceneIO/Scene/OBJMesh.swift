import Geometry
import SceneDescription
import PlatformSupport

/// A triangulated OBJ mesh, in the file's Double precision.
///
/// The faces are kept as the scene keeps them (`TriangleMesh`): three
/// Int32 indices a triangle per attribute, 12 bytes where a triangle of
/// `OBJTriangle`s took 48, and the scene's mesh shares them rather than
/// copying them. `triangles` gives them as `OBJTriangle`s.
package struct OBJMesh: Sendable {
  /// The `v` lines in order; x, y and z only.
  package var vertices: [Vector3<Double>]
  /// The `vn` lines in order, as written (not normalised; may be zero).
  package var normals: [Vector3<Double>]
  /// The `vt` lines in order, (u, v); a missing v is 0, w is dropped.
  package var textureCoordinates: [TextureCoordinate<Double>]
  /// Three per triangle, into `vertices`: the faces, fanned into
  /// triangles, in file order.
  package private(set) var vertexIndices: [Int32] = []
  /// Three per triangle into `normals`, −1s for a face without; empty
  /// until some face gives normals.
  package private(set) var normalIndices: [Int32] = []
  /// Three per triangle into `textureCoordinates`, −1s for a face without;
  /// empty until some face gives texture coordinates.
  package private(set) var textureIndices: [Int32] = []

  package init(
    vertices: [Vector3<Double>] = [], normals: [Vector3<Double>] = [],
    textureCoordinates: [TextureCoordinate<Double>] = [],
    triangles: [OBJTriangle] = []
  ) {
    self.vertices = vertices
    self.normals = normals
    self.textureCoordinates = textureCoordinates
    self.triangles = triangles
  }

  /// The count of triangles.
  package var triangleCount: Int { vertexIndices.count / 3 }

  /// The faces, fanned into triangles, in file order, one value each (made
  /// on each read: for tests and small meshes).
  package var triangles: [OBJTriangle] {
    get { (0..<triangleCount).map(face) }
    set {
      vertexIndices = []
      normalIndices = []
      textureIndices = []
      for face in newValue { append(face) }
    }
  }

  /// Triangle `index` as an `OBJTriangle`.
  package func face(_ index: Int) -> OBJTriangle {
    func triple(_ indices: [Int32]) -> SIMD3<Int32>? {
      guard !indices.isEmpty, indices[3 * index] >= 0 else { return nil }
      return SIMD3(
        indices[3 * index], indices[3 * index + 1], indices[3 * index + 2])
    }
    return OBJTriangle(
      vertexIndices: triple(vertexIndices) ?? SIMD3(repeating: -1),
      normalIndices: triple(normalIndices),
      textureIndices: triple(textureIndices))
  }

  /// Appends a triangle.
  mutating func append(_ face: OBJTriangle) {
    append(
      vertices: face.vertexIndices, normals: face.normalIndices,
      texture: face.textureIndices)
  }

  /// Appends a triangle: its vertex indices and, when its face gave them,
  /// its normal and texture-coordinate indices.
  @inline(__always)
  mutating func append(
    vertices v: SIMD3<Int32>, normals n: SIMD3<Int32>?,
    texture t: SIMD3<Int32>?
  ) {
    let previous = vertexIndices.count
    vertexIndices.append(v.x)
    vertexIndices.append(v.y)
    vertexIndices.append(v.z)
    Self.append(n, to: &normalIndices, previous: previous)
    Self.append(t, to: &textureIndices, previous: previous)
  }

  /// Appends `triple`, or −1s, to `indices`, which hold `previous` entries
  /// or none at all while no face gave any.
  @inline(__always)
  private static func append(
    _ triple: SIMD3<Int32>?, to indices: inout [Int32], previous: Int
  ) {
    if let triple {
      if indices.isEmpty && previous > 0 {
        indices = Array(repeating: -1, count: previous)
      }
      indices.append(triple.x)
      indices.append(triple.y)
      indices.append(triple.z)
    } else if !indices.isEmpty {
      indices.append(-1)
      indices.append(-1)
      indices.append(-1)
    }
  }

  /// Appends `other`'s elements after this mesh's, and its faces, whose
  /// indices already count this mesh's elements (a later part of a
  /// file, `OBJReader.parseInParts`).
  mutating func append(contentsOf other: OBJMesh) {
    let (previous, added) = (vertexIndices.count, other.vertexIndices.count)
    vertices += other.vertices
    normals += other.normals
    textureCoordinates += other.textureCoordinates
    vertexIndices += other.vertexIndices
    func merge(_ indices: inout [Int32], _ others: [Int32]) {
      guard !indices.isEmpty || !others.isEmpty else { return }
      if indices.isEmpty { indices = Array(repeating: -1, count: previous) }
      if others.isEmpty {
        indices += repeatElement(-1, count: added)
      } else {
        indices += others
      }
    }
    merge(&normalIndices, other.normalIndices)
    merge(&textureIndices, other.textureIndices)
  }

  /// Room for `count` vertex index entries, and as many of each other
  /// kind the mesh has.
  mutating func reserveIndices(_ count: Int) {
    vertexIndices.reserveCapacity(count)
    if !normalIndices.isEmpty { normalIndices.reserveCapacity(count) }
    if !textureIndices.isEmpty { textureIndices.reserveCapacity(count) }
  }

  /// Drops the index entries past `counts` (vertex, normal, texture).
  mutating func truncateIndices(to counts: (Int, Int, Int)) {
    vertexIndices.removeLast(vertexIndices.count - counts.0)
    normalIndices.removeLast(normalIndices.count - counts.1)
    textureIndices.removeLast(textureIndices.count - counts.2)
  }

  /// Whether any face gives texture coordinates.
  package var hasTextureCoordinates: Bool {
    stride(from: 0, to: textureIndices.count, by: 3).contains {
      textureIndices[$0] >= 0
    }
  }

  /// The mesh with a normal per vertex where it has none (no `vn` lines),
  /// by the style's rule (see `MeshNormals`); vertices are taken by index,
  /// coincident positions are not merged. Faces whose cross product is zero
  /// or not finite add nothing; a vertex whose sum is zero gets the zero
  /// normal, for which a hit falls back to the face's own normal.
  package func smoothed(_ rule: MeshNormals = .unitMean) -> OBJMesh {
    guard let normals = smoothedNormals(rule) else { return self }
    var result = self
    result.normals = normals
    result.normalIndices = vertexIndices
    return result
  }

  /// The normal per vertex of `smoothed`, or nil when `smoothed` leaves
  /// the mesh as it is (it has `vn` lines, or no faces).
  ///
  /// A large mesh is summed by up to `threads` threads, each owning a
  /// range of vertices: each reads every face in order and adds its normal
  /// to the corners it owns, so every vertex's sum is added in the faces'
  /// order, and the normals are the same bit for bit for any count.
  func smoothedNormals(_ rule: MeshNormals, threads: Int = 1)
    -> [Vector3<Double>]?
  {
    guard normals.isEmpty, !vertexIndices.isEmpty else { return nil }
    let parts = Parallel.parts(
      vertices.count, threads: threads, from: 1 << 16, minimum: 1 << 14)
    return [Vector3<Double>](unsafeUninitializedCapacity: vertices.count) {
      sums, count in
      Parallel.inParts(vertices.count, parts) { _, owned in
        let sums = sums.baseAddress!
        (sums + owned.lowerBound).initialize(
          repeating: .zero, count: owned.count)
        for first in stride(from: 0, to: vertexIndices.count, by: 3) {
          let (a, b, c) = (
            Int(vertexIndices[first]), Int(vertexIndices[first + 1]),
            Int(vertexIndices[first + 2])
          )
          let adds = (owned ~= a, owned ~= b, owned ~= c)
          guard adds.0 || adds.1 || adds.2 else { continue }
          let cross = (vertices[b] - vertices[a]).cross(
            vertices[c] - vertices[a])
          guard cross.maxMagnitude > 0, cross.isFinite else { continue }
          let weighted = rule == .unitMean ? cross.normalized() : cross
          if adds.0 { sums[a] += weighted }
          if adds.1 { sums[b] += weighted }
          if adds.2 { sums[c] += weighted }
        }
        for index in owned {
          let sum = sums[index]
          sums[index] =
            sum.maxMagnitude > 0 && sum.isFinite ? sum.normalized() : .zero
        }
      }
      count = vertices.count
    }
  }

  /// The course loader's reading of `a/b` faces in a file that has both
  /// `vt` and `vn` lines, for a material without a texture: b is a normal
  /// index. Faces that give normals already are unchanged.
  ///
  /// - Returns: nil when some such b is not a valid normal index.
  package func readingTextureIndicesAsNormals() -> OBJMesh? {
    guard !normals.isEmpty, !textureIndices.isEmpty else { return self }
    var result = self
    let limit = Int32(truncatingIfNeeded: normals.count)
    for first in stride(from: 0, to: textureIndices.count, by: 3) {
      guard normalIndices.isEmpty || normalIndices[first] < 0,
        textureIndices[first] >= 0
      else { continue }
      let second = (
        textureIndices[first], textureIndices[first + 1],
        textureIndices[first + 2]
      )
      guard Swift.max(second.0, second.1, second.2) < limit else {
        return nil
      }
      if result.normalIndices.isEmpty {
        result.normalIndices = Array(repeating: -1, count: vertexIndices.count)
      }
      result.normalIndices[first] = second.0
      result.normalIndices[first + 1] = second.1
      result.normalIndices[first + 2] = second.2
      result.textureIndices[first] = -1
      result.textureIndices[first + 1] = -1
      result.textureIndices[first + 2] = -1
    }
    return result
  }
}

/// One triangle of an OBJ mesh: 0-based indices into `OBJMesh.vertices`
/// and, when its face gave them, into `OBJMesh.normals` and
/// `OBJMesh.textureCoordinates`.
package struct OBJTriangle: Hashable, Sendable {
  package var vertexIndices: SIMD3<Int32>
  /// −1s when the face gave no normals; read through `normalIndices`.
  @usableFromInline var normalStorage: SIMD3<Int32>
  /// −1s when the face gave no texture coordinates.
  @usableFromInline var textureStorage: SIMD3<Int32>

  package init(
    vertexIndices: SIMD3<Int32>, normalIndices: SIMD3<Int32>? = nil,
    textureIndices: SIMD3<Int32>? = nil
  ) {
    self.vertexIndices = vertexIndices
    normalStorage = normalIndices ?? SIMD3(repeating: -1)
    textureStorage = textureIndices ?? SIMD3(repeating: -1)
  }

  /// Indices into `OBJMesh.normals`, or nil for a face without normals.
  @inlinable
  package var normalIndices: SIMD3<Int32>? {
    get { normalStorage.x < 0 ? nil : normalStorage }
    set { normalStorage = newValue ?? SIMD3(repeating: -1) }
  }

  /// Indices into `OBJMesh.textureCoordinates`, or nil.
  @inlinable
  package var textureIndices: SIMD3<Int32>? {
    get { textureStorage.x < 0 ? nil : textureStorage }
    set { textureStorage = newValue ?? SIMD3(repeating: -1) }
  }
}

extension OBJMesh: Hashable {
  /// The same elements and the same faces, however the indices are held
  /// (−1s or none for faces without normals).
  package static func == (lhs: OBJMesh, rhs: OBJMesh) -> Bool {
    lhs.vertices == rhs.vertices && lhs.normals == rhs.normals
      && lhs.textureCoordinates == rhs.textureCoordinates
      && lhs.vertexIndices == rhs.vertexIndices
      && lhs.triangles == rhs.triangles
  }

  package func hash(into hasher: inout Hasher) {
    hasher.combine(vertices)
    hasher.combine(normals)
    hasher.combine(textureCoordinates)
    hasher.combine(vertexIndices)
  }
}
