/// A mesh file's triangles as the scene keeps them (`TriangleMesh`).
extension TriangleMesh<Double> {
  /// The mesh of `obj`, every triangle of material `materialIndex`, the
  /// same triangles as `obj.smoothed(normals).makeTriangles(…)` in the same
  /// order: where the file has no `vn` lines, a normal per vertex by the
  /// rule (`OBJMesh.smoothed`), indexed by the vertex indices themselves.
  init(_ obj: consuming OBJMesh, materialIndex: Int, normals rule: MeshNormals)
  {
    let faces = obj.triangles
    let smoothed = obj.smoothedNormals(rule)
    let hasNormals =
      smoothed == nil && faces.contains { $0.normalIndices != nil }
    let hasTexture = faces.contains { $0.textureIndices != nil }
    var vertexIndices: [Int32] = []
    var normalIndices: [Int32] = []
    var textureIndices: [Int32] = []
    vertexIndices.reserveCapacityOnHugePages(3 * faces.count)
    if hasNormals { normalIndices.reserveCapacity(3 * faces.count) }
    if hasTexture { textureIndices.reserveCapacity(3 * faces.count) }
    for face in faces {
      let v = face.vertexIndices
      vertexIndices.append(v.x)
      vertexIndices.append(v.y)
      vertexIndices.append(v.z)
      // −1s where the face gave none, as `OBJTriangle` stores them.
      if hasNormals {
        let n = face.normalStorage
        normalIndices.append(n.x)
        normalIndices.append(n.y)
        normalIndices.append(n.z)
      }
      if hasTexture {
        let t = face.textureStorage
        textureIndices.append(t.x)
        textureIndices.append(t.y)
        textureIndices.append(t.z)
      }
    }
    self.init(
      vertices: obj.vertices, normals: smoothed ?? obj.normals,
      textureCoordinates: obj.textureCoordinates,
      vertexIndices: vertexIndices, normalIndices: normalIndices,
      normalsFollowVertices: smoothed != nil, textureIndices: textureIndices,
      materialIndex: materialIndex)
  }
}
