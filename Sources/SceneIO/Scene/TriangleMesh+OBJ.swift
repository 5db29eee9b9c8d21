import Geometry
import SceneDescription

/// A mesh file's triangles as the scene keeps them (`TriangleMesh`).
extension TriangleMesh<Double> {
  /// The mesh of `obj`, every triangle of material `materialIndex`, face
  /// by face in the file's order: where the file has no `vn` lines, a
  /// normal per vertex by the rule (`OBJMesh.smoothed`), indexed by the
  /// vertex indices themselves, summed by up to `threads` threads.
  init(
    _ obj: consuming OBJMesh, materialIndex: Int, normals rule: MeshNormals,
    threads: Int = 1
  ) {
    // The file's index arrays themselves, shared: no copy.
    let smoothed = obj.smoothedNormals(rule, threads: threads)
    self.init(
      vertices: obj.vertices, normals: smoothed ?? obj.normals,
      textureCoordinates: obj.textureCoordinates,
      vertexIndices: obj.vertexIndices,
      normalIndices: smoothed == nil ? obj.normalIndices : [],
      normalsFollowVertices: smoothed != nil,
      textureIndices: obj.textureIndices,
      materialIndex: materialIndex)
  }
}
