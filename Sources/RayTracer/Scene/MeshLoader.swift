/// Turns an OBJ file into a scene object, as both scene formats name it
/// (`TriangleMesh { obj_file PATH }` in text, `objFile NAME` in a plist).
///
/// Normals: a file with `vn` lines uses them; otherwise the mesh is
/// smoothed by the style's rule (`MeshNormals`). A face written `a/b` in a
/// file with both `vt` and `vn` lines reads b as a texture coordinate for a
/// textured material and as a normal otherwise, as the course's loader
/// does.
enum MeshLoader {
  /// A mesh as the scene holds it.
  struct Loaded {
    /// A group of the mesh's triangles.
    var object: SceneObject<Double>
    /// Whether any face gives texture coordinates.
    var hasTextureCoordinates: Bool
  }

  enum Failure: Error {
    /// A problem inside the OBJ file, at its own line and column.
    case inFile(SceneError)
    /// A problem the scene reports where it names the mesh.
    case atReference(String)
  }

  static func load(
    _ path: String, materialIndex: Int, textured: Bool, normals: MeshNormals,
    precision: Precision = .double
  ) throws(Failure) -> Loaded {
    var mesh: OBJMesh
    do {
      mesh = try OBJReader.read(contentsOf: path, precision: precision)
    } catch {
      guard error.line == 0 else { throw .inFile(error) }
      throw .atReference(
        "cannot read '\(SceneParser.escaped(path))': \(error.message)")
    }
    if !textured {
      guard let reread = mesh.readingTextureIndicesAsNormals() else {
        throw .atReference(
          "'\(SceneParser.escaped(path))' has faces a/b whose b, read as a "
            + "normal for a material without a texture, is not a vn index")
      }
      mesh = reread
    }
    // The triangles side by side in one array on 2 MiB pages, the scene's
    // one entry for the file (`TriangleMesh`).
    let smoothed = mesh.smoothed(normals)
    var triangles: [Triangle<Double>] = []
    triangles.reserveCapacityOnHugePages(smoothed.triangles.count)
    for index in smoothed.triangles.indices {
      triangles.append(
        smoothed.triangle(at: index, materialIndex: materialIndex))
    }
    return Loaded(
      object: .mesh(TriangleMesh(triangles)),
      hasTextureCoordinates: mesh.hasTextureCoordinates)
  }
}
