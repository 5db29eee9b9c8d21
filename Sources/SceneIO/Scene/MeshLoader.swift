import Geometry
import SceneDescription
import PlatformSupport

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

  /// The meshes one scene has read, by how they were read: a file the
  /// scene names many times is read and stored once, each use sharing its
  /// arrays with its own material (`TriangleMesh.withMaterial`).
  final class Cache: Sendable {
    struct Key: Hashable {
      var file: FileIdentity.Key
      var textured: Bool
      var normals: MeshNormals
      var precision: NumberRange
    }
    let loaded = Locked<[Key: Loaded]>([:])
  }

  /// `load`, from `cache` when the same file was read the same way.
  static func load(
    _ path: String, materialIndex: Int, textured: Bool, normals: MeshNormals,
    precision: NumberRange = .double, threads: Int, cache: Cache
  ) throws(Failure) -> Loaded {
    guard let file = FileIdentity.key(path) else {
      return try load(
        path, materialIndex: materialIndex, textured: textured,
        normals: normals, precision: precision, threads: threads)
    }
    let key = Cache.Key(
      file: file, textured: textured, normals: normals, precision: precision)
    if var found = cache.loaded.withLock({ $0[key] }),
      case .mesh(let mesh) = found.object
    {
      found.object = .mesh(mesh.withMaterial(materialIndex))
      return found
    }
    let loaded = try load(
      path, materialIndex: materialIndex, textured: textured,
      normals: normals, precision: precision, threads: threads)
    cache.loaded.withLock { $0[key] = loaded }
    return loaded
  }

  /// The mesh of the OBJ file at `path`, read and parsed by up to
  /// `threads` threads (the same mesh for any count).
  static func load(
    _ path: String, materialIndex: Int, textured: Bool, normals: MeshNormals,
    precision: NumberRange = .double, threads: Int
  ) throws(Failure) -> Loaded {
    if let problem = MemoryNeed.problem(reading: path, perByte: 6) {
      throw .atReference(problem)
    }
    var mesh: OBJMesh
    do {
      mesh = try OBJReader.read(
        contentsOf: path, precision: precision, threads: threads)
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
    // The scene's one entry for the file, indexed as the file is
    // (`TriangleMesh`).
    let hasTextureCoordinates = mesh.hasTextureCoordinates
    let triangles = TriangleMesh(
      consume mesh, materialIndex: materialIndex, normals: normals,
      threads: threads)
    return Loaded(
      object: .mesh(triangles), hasTextureCoordinates: hasTextureCoordinates)
  }
}
