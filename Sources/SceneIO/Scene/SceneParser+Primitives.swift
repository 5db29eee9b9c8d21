import Geometry
import SceneDescription
import PlatformSupport

/// The text format's own kinds of object: Triangle, TriangleMesh (with
/// the path of its OBJ file), Sphere and Plane.
extension SceneParser {
  mutating func parseTriangle(material: Int) throws(SceneError)
    -> Triangle<Double>
  {
    var vertices: [Vector3<Double>?] = [nil, nil, nil]
    let close = try parseFields(
      "Triangle", ["vertex0", "vertex1", "vertex2"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      let index = field == "vertex0" ? 0 : field == "vertex1" ? 1 : 2
      vertices[index] = try parser.vector()
    }
    guard let v0 = vertices[0], let v1 = vertices[1], let v2 = vertices[2]
    else {
      throw missing(
        "Triangle",
        [
          ("vertex0", vertices[0] != nil), ("vertex1", vertices[1] != nil),
          ("vertex2", vertices[2] != nil),
        ], close)
    }
    return Triangle(v0, v1, v2, materialIndex: material)
  }

  /// `TriangleMesh { obj_file PATH }`, the path relative to the scene
  /// file's folder; the mesh is one object, a group of its triangles.
  mutating func parseTriangleMesh(material: Int) throws(SceneError)
    -> SceneObject<Double>
  {
    var path: (String, SceneToken)?
    let close = try parseFields(
      "TriangleMesh", ["obj_file"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      path = try parser.path(after: field)
    }
    guard let (relative, token) = path else {
      throw missing("TriangleMesh", [("obj_file", false)], close)
    }
    let resolved = resolved(relative, folder: "Meshes", fileExtension: "obj")
    let textured = parsedMaterials.map {
      $0.indices.contains(material) && $0[material].texturePath != nil
    }
    do {
      let mesh = try MeshLoader.load(
        resolved, materialIndex: material, textured: textured ?? false,
        normals: options.meshNormals, precision: options.precision,
        threads: options.threads, cache: meshCache)
      meshFiles.append(resolved)
      if !mesh.hasTextureCoordinates {
        meshesWithoutTextureCoordinates.append((material, token, resolved))
      }
      return mesh.object
    } catch {
      switch error {
      case .inFile(let inner): throw inner
      case .atReference(let message): throw self.error(at: token, message)
      }
    }
  }

  /// The path after `field`, as written: `text` escapes control characters,
  /// which would name another file.
  mutating func path(
    after field: String
  ) throws(SceneError) -> (String, SceneToken) {
    let token = try next()
    guard token.kind == .word else {
      throw error(at: token, "expected a file's path after '\(field)'")
    }
    return (tokenizer.text(of: token), token)
  }

  /// `relative` against the scene file's folder; absolute paths as given.
  func resolved(_ relative: String) -> String {
    if relative.hasPrefix("/") { return relative }
    guard let slash = file.lastIndex(of: "/") else { return relative }
    return String(file[...slash]) + relative
  }

  /// `resolved(relative)`, or, when that names no file, the first file of
  /// the course's loader's lookup by name that exists (`ResourceLookup`:
  /// `obj_file cube` finds `Meshes/cube.obj`, as a property list's
  /// `objFile` does). Nothing found: the path as written, whose reading
  /// then says what is wrong with it.
  func resolved(
    _ relative: String, folder: String, fileExtension: String
  ) -> String {
    let literal = resolved(relative)
    if ResourceLookup.existing([literal]) != nil { return literal }
    return ResourceLookup.existing(
      ResourceLookup.candidates(
        relative, folder: folder, fileExtension: fileExtension,
        besideScene: file)) ?? literal
  }

  /// The hot path of large scenes: keywords are compared as bytes, and
  /// nothing is allocated. The same checks and messages as `parseFields`
  /// with `positive` for the radius. The plain form, nearly every sphere
  /// of a generated scene, is read in one pass first; whatever that pass
  /// leaves, errors included, is read token by token.
  mutating func parseSphere(material: Int) throws(SceneError) -> Sphere<
    Double
  > {
    let start = tokenizer.position
    if readsPlainSpheres, let (center, radius) = tokenizer.plainSphere() {
      let precision = options.precision
      if radius > 0, precision.holds(radius), precision.holds(center.x),
        precision.holds(center.y), precision.holds(center.z)
      {
        return Sphere(center: center, radius: radius, materialIndex: material)
      }
      // The error at the radius, or at a number the precision cannot
      // hold, comes from the reading below.
      tokenizer.position = start
    }
    try expect(.open, "'{' after Sphere")
    var center: Vector3<Double>?
    var radius: Double?
    while true {
      let token = try next()
      switch token.kind {
      case .close:
        guard let center, let radius else {
          throw missing(
            "Sphere", [("center", center != nil), ("radius", radius != nil)],
            token)
        }
        return Sphere(center: center, radius: radius, materialIndex: material)
      case .end, .open:
        throw unexpectedEnd(token, in: "Sphere")
      case .word:
        if tokenizer.matches(token, "center") {
          guard center == nil else {
            throw error(at: token, "'center' is given twice in Sphere")
          }
          center = try vector()
        } else if tokenizer.matches(token, "radius") {
          guard radius == nil else {
            throw error(at: token, "'radius' is given twice in Sphere")
          }
          radius = try positive("radius")
        } else {
          throw unexpected(
            token, expected: "a field of Sphere", choices: ["center", "radius"])
        }
      }
    }
  }

  mutating func parsePlane(material: Int) throws(SceneError) -> Plane<
    Double
  > {
    var normal: Vector3<Double>?
    var offset: (Double, SceneToken)?
    let close = try parseFields(
      "Plane", ["normal", "offset"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      if field == "normal" {
        normal = try parser.nonZeroVector(field)
      } else {
        let token = parser.peekStart()
        offset = (try parser.number(), token)
      }
    }
    guard let normal, let offset else {
      throw missing(
        "Plane", [("normal", normal != nil), ("offset", offset != nil)], close)
    }
    let plane = Plane(normal: normal, offset: offset.0, materialIndex: material)
    // Dividing by the normal's length overflows for a tiny normal and a
    // large offset (`normal 0 0 1e-150  offset 1e300`): the plane lies
    // beyond Double's range, and an infinite offset must not reach a render.
    guard plane.offset.isFinite else {
      throw error(
        at: offset.1,
        "the plane is too far from the origin: offset \(text(offset.1)) "
          + "divided by the normal's length is not a finite number")
    }
    return plane
  }
}
