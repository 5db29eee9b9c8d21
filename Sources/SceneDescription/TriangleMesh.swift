import Geometry

/// The triangles of one mesh file (the course's `TriangleMesh { obj_file … }`),
/// hit as a group of them.
///
/// Kept as the file keeps them, indexed: shared vertex, normal and
/// texture-coordinate arrays and three indices per triangle, about 36 bytes
/// a triangle for a smoothed mesh of a vertex per two triangles, where an
/// array of `Triangle` values took 216. The triangles are made on demand
/// (`triangle(at:)`, or the mesh as a collection of them), each the same
/// value, bit for bit, as the one the file's face describes. A group's
/// triangle entries are boxed, a heap allocation apiece; the mesh is one
/// entry however many triangles it has, and `Group.flattened` hands it on
/// without copying it when it is not transformed.
///
/// Loose triangles appended one by one (`append`, as `TriangleList` keeps
/// them) get three vertices each and, per triangle, their own material.
public struct TriangleMesh<Scalar: RayScalar>: Hashable, Sendable {
  /// Positions, shared by the triangles that index them.
  @usableFromInline package var vertices: [Vector3<Scalar>] = []
  /// Normals, as given (not normalised); indexed by `normalIndices`, or by
  /// the vertex indices when `normalsFollowVertices`.
  @usableFromInline package var normals: [Vector3<Scalar>] = []
  @usableFromInline package private(set) var textureCoordinates:
    [TextureCoordinate<Scalar>] = []
  /// Three per triangle, into `vertices`, in the order of its vertices.
  @usableFromInline package private(set) var vertexIndices: [Int32] = []
  /// Three per triangle into `normals`, −1s for a triangle without vertex
  /// normals; may be empty when no triangle has them, and is empty when
  /// `normalsFollowVertices`.
  @usableFromInline package private(set) var normalIndices: [Int32] = []
  /// Whether every triangle's normals are those of its vertices,
  /// `normals[vertexIndices[…]]`: a smoothed mesh, a normal per vertex.
  @usableFromInline package private(set) var normalsFollowVertices = false
  /// Three per triangle into `textureCoordinates`, −1s for a triangle
  /// without; may be empty when no triangle has them.
  @usableFromInline package private(set) var textureIndices: [Int32] = []
  /// Every triangle's material, unless `materialIndices` gives one each.
  public private(set) var materialIndex = 0
  /// One per triangle, or empty when all have `materialIndex`.
  @usableFromInline package private(set) var materialIndices: [Int] = []
  /// Which reading of a file the arrays come from: the same for every copy
  /// and `withMaterial` of one mesh, so that a renderer can build what it
  /// needs of a mesh once however often the scene names it. It takes no
  /// part in comparing meshes.
  package var storage = StorageTag()

  /// A tag equal to every other: meshes compare by their triangles.
  package struct StorageTag: Hashable, Sendable {
    private final class Token: Sendable {}
    private let token = Token()
    package init() {}
    package var identity: ObjectIdentifier { ObjectIdentifier(token) }
    package static func == (_: StorageTag, _: StorageTag) -> Bool { true }
    package func hash(into hasher: inout Hasher) {}
  }

  /// An empty mesh, for `append`.
  public init() {}

  /// The triangles, in order, each with three vertices of its own.
  public init(_ triangles: [Triangle<Scalar>]) {
    vertices.reserveCapacity(3 * triangles.count)
    vertexIndices.reserveCapacity(3 * triangles.count)
    materialIndices.reserveCapacity(triangles.count)
    for triangle in triangles { append(triangle) }
  }

  /// A mesh of one material from its arrays.
  ///
  /// - Precondition: `vertexIndices` holds three valid indices per
  ///   triangle; `normalIndices` and `textureIndices` are empty or of the
  ///   same length, each triple valid or three −1s; with
  ///   `normalsFollowVertices`, `normals` has one per vertex and
  ///   `normalIndices` is empty.
  public init(
    vertices: [Vector3<Scalar>], normals: [Vector3<Scalar>],
    textureCoordinates: [TextureCoordinate<Scalar>], vertexIndices: [Int32],
    normalIndices: [Int32], normalsFollowVertices: Bool,
    textureIndices: [Int32], materialIndex: Int
  ) {
    self.vertices = vertices
    self.normals = normals
    self.textureCoordinates = textureCoordinates
    self.vertexIndices = vertexIndices
    self.normalIndices = normalIndices
    self.normalsFollowVertices = normalsFollowVertices
    self.textureIndices = textureIndices
    self.materialIndex = materialIndex
  }

  /// Appends `triangle` with three vertices, normals and texture
  /// coordinates of its own, and its own material.
  public mutating func append(_ triangle: Triangle<Scalar>) {
    storage = StorageTag()
    let previous = count
    if materialIndices.isEmpty && previous > 0 {
      materialIndices = Array(repeating: materialIndex, count: previous)
    }
    if previous == 0 { materialIndex = triangle.materialIndex }
    materialIndices.append(triangle.materialIndex)
    func next(_ array: [some Any]) -> Int32 {
      Int32(truncatingIfNeeded: array.count)
    }
    let v = next(vertices)
    vertices.append(triangle.v0)
    vertices.append(triangle.v1)
    vertices.append(triangle.v2)
    appendTriple(&vertexIndices, v)
    if let given = triangle.vertexNormals {
      if normalsFollowVertices {
        // A mesh of normals by vertex gains a triangle of its own.
        normalIndices = Array(vertexIndices.prefix(3 * previous))
        normalsFollowVertices = false
      } else if normalIndices.isEmpty {
        normalIndices = Array(repeating: -1, count: 3 * previous)
      }
      let n = next(normals)
      normals.append(given.n0)
      normals.append(given.n1)
      normals.append(given.n2)
      appendTriple(&normalIndices, n)
    } else if normalsFollowVertices {
      normalIndices = Array(vertexIndices.prefix(3 * previous)) + [-1, -1, -1]
      normalsFollowVertices = false
    } else if !normalIndices.isEmpty {
      appendTriple(&normalIndices, -1, step: 0)
    }
    if let given = triangle.textureCoordinates {
      if textureIndices.isEmpty {
        textureIndices = Array(repeating: -1, count: 3 * previous)
      }
      let t = next(textureCoordinates)
      textureCoordinates.append(given.t0)
      textureCoordinates.append(given.t1)
      textureCoordinates.append(given.t2)
      appendTriple(&textureIndices, t)
    } else if !textureIndices.isEmpty {
      appendTriple(&textureIndices, -1, step: 0)
    }
  }

  /// Appends first, first + step, first + 2·step.
  private func appendTriple(
    _ indices: inout [Int32], _ first: Int32, step: Int32 = 1
  ) {
    indices.append(first)
    indices.append(first + step)
    indices.append(first + 2 * step)
  }

  /// The indices into `vertices` of triangle `index`'s v0, v1 and v2.
  @inlinable @inline(__always)
  package func corners(_ index: Int) -> (Int, Int, Int) {
    (
      Int(vertexIndices[3 * index]), Int(vertexIndices[3 * index + 1]),
      Int(vertexIndices[3 * index + 2])
    )
  }

  /// Triangle `index`'s indices into `normals`, or nil when it has none.
  @inlinable @inline(__always)
  package func normalCorners(_ index: Int) -> (Int, Int, Int)? {
    normalsFollowVertices
      ? corners(index) : Self.corners(index, in: normalIndices)
  }

  /// Triangle `index`'s indices into `textureCoordinates`, or nil.
  @inlinable @inline(__always)
  package func textureCorners(_ index: Int) -> (Int, Int, Int)? {
    Self.corners(index, in: textureIndices)
  }

  /// Triangle `index`'s three entries of a per-corner index array, or nil
  /// when the array is empty or the triangle's entries are −1 (none).
  @inlinable @inline(__always)
  static func corners(_ index: Int, in indices: [Int32])
    -> (Int, Int, Int)?
  {
    guard !indices.isEmpty, indices[3 * index] >= 0 else { return nil }
    return (
      Int(indices[3 * index]), Int(indices[3 * index + 1]),
      Int(indices[3 * index + 2])
    )
  }

  /// The same triangles, every one of `materialIndex`: the arrays are
  /// shared, not copied (a mesh file a scene names several times is held
  /// once).
  public func withMaterial(_ materialIndex: Int) -> TriangleMesh {
    var copy = self
    copy.materialIndex = materialIndex
    copy.materialIndices = []
    return copy
  }

  /// Triangle `index`'s material.
  @inlinable @inline(__always)
  package func material(at index: Int) -> Int {
    materialIndices.isEmpty ? materialIndex : materialIndices[index]
  }

  /// Triangle `index`'s three vertices.
  @inlinable @inline(__always)
  package func vertices(at index: Int) -> (
    Vector3<Scalar>, Vector3<Scalar>, Vector3<Scalar>
  ) {
    let (a, b, c) = corners(index)
    return (vertices[a], vertices[b], vertices[c])
  }

  /// Triangle `index`, as its face gave it.
  ///
  /// - Precondition: `indices.contains(index)`.
  @inlinable public func triangle(at index: Int) -> Triangle<Scalar> {
    let (v0, v1, v2) = vertices(at: index)
    return Triangle(
      v0, v1, v2,
      vertexNormals: normalCorners(index).map {
        Triangle.VertexNormals(normals[$0.0], normals[$0.1], normals[$0.2])
      },
      textureCoordinates: textureCorners(index).map {
        Triangle.TextureCoordinates(
          textureCoordinates[$0.0], textureCoordinates[$0.1],
          textureCoordinates[$0.2])
      },
      materialIndex: material(at: index))
  }
}

extension TriangleMesh: RandomAccessCollection {
  @inlinable public var startIndex: Int { 0 }
  @inlinable public var endIndex: Int { vertexIndices.count / 3 }
  @inlinable public subscript(position: Int) -> Triangle<Scalar> {
    triangle(at: position)
  }
}
