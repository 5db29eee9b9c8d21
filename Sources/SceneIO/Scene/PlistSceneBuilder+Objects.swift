import Geometry
import SceneDescription
import PlatformSupport

#if canImport(FoundationEssentials)
  import FoundationEssentials
#else
  import Foundation
#endif

/// The objects of a property-list scene's group.
extension PlistSceneBuilder {
  // MARK: - Objects

  mutating func group(
    _ value: PropertyList, _ path: String, depth: Int, material: Int?
  ) throws(SceneError) -> Group<Double> {
    var objects: [SceneObject<Double>] = []
    for (index, object) in try array(value, path).enumerated() {
      objects.append(
        try self.object(
          object, "\(path)[\(index)]", depth: depth, inherited: material))
    }
    return Group(objects)
  }

  static let objectTypes = [
    "Sphere", "Plane", "Triangle", "TriangleMesh", "Group", "Transform",
  ]

  /// The object at `path`. Its material is `forced` (a Transform's own
  /// index) when given, else its `materialIndex`, else `inherited`, else 0.
  mutating func object(
    _ value: PropertyList, _ path: String, depth: Int, inherited: Int?,
    forced: Int? = nil
  ) throws(SceneError) -> SceneObject<Double> {
    let fields = try dictionary(value, path)
    if case .string(let name)? = fields["type"],
      let kind = options.shapes.first(where: { $0.name == name })
    {
      return try shape(
        kind, fields, path, material: own(fields, path, forced, inherited))
    }
    let type = try checkType(
      fields, Self.objectTypes + options.shapes.map(\.name), path,
      required: true)
    let own = try materialIndex(fields, path)
    let material = forced ?? own ?? inherited ?? 0
    switch type {
    case "Sphere":
      try checkKeys(
        fields, ["type", "materialIndex", "center", "radius"], path)
      let center = try required(vector(fields, "center", path), "center", path)
      let radius = try required(number(fields, "radius", path), "radius", path)
      guard radius > 0 else {
        throw fail(
          "\(path).radius",
          "'radius' must be positive, found \(quoted(fields["radius"]))")
      }
      return .sphere(
        Sphere(center: center, radius: radius, materialIndex: material))
    case "Plane":
      try checkKeys(
        fields, ["type", "materialIndex", "normal", "offset"], path)
      let normal = try required(vector(fields, "normal", path), "normal", path)
      let offset = try required(number(fields, "offset", path), "offset", path)
      guard normal.maxMagnitude > 0 else {
        throw fail("\(path).normal", "'normal' must not be the zero vector")
      }
      // n·P + offset = 0 is the text format's n·P = −offset.
      let plane = Plane(
        normal: normal, offset: -offset, materialIndex: material)
      guard plane.offset.isFinite else {
        throw fail(
          "\(path).offset",
          "the plane is too far from the origin: the offset divided by the "
            + "normal's length is not a finite number")
      }
      return .plane(plane)
    case "Triangle":
      let names = ["vertex0", "vertex1", "vertex2"]
      try checkKeys(fields, ["type", "materialIndex"] + names, path)
      var vertices: [Vector3<Double>] = []
      for name in names {
        vertices.append(try required(vector(fields, name, path), name, path))
      }
      return .triangle(
        Triangle(
          vertices[0], vertices[1], vertices[2], materialIndex: material))
    case "TriangleMesh":
      try checkKeys(fields, ["type", "materialIndex", "objFile"], path)
      return try mesh(fields, path, material: material)
    case "Group":
      try checkKeys(fields, ["type", "materialIndex", "Group"], path)
      try checkDepth(depth, path)
      let inner = try required(fields["Group"], "Group", path)
      return .group(
        try group(
          inner, "\(path).Group", depth: depth + 1, material: own ?? inherited))
    default:
      try checkKeys(
        fields, ["type", "materialIndex", "transforms", "transformed"], path)
      try checkDepth(depth, path)
      return .transform(
        try transform(
          fields, path, depth: depth, inherited: inherited, own: own))
    }
  }

  mutating func transform(
    _ fields: [String: PropertyList], _ path: String, depth: Int,
    inherited: Int?, own: Int?
  ) throws(SceneError) -> Transform<Double> {
    var matrix = Matrix4<Double>.identity
    if let list = fields["transforms"] {
      for (index, operation) in try array(list, "\(path).transforms")
        .enumerated()
      {
        matrix =
          matrix
          * (try self.operation(operation, "\(path).transforms[\(index)]"))
      }
    }
    let child = try required(fields["transformed"], "transformed", path)
    openTransforms += 1
    let object = try self.object(
      child, "\(path).transformed", depth: depth + 1, inherited: inherited,
      forced: own)
    openTransforms -= 1
    guard matrix.rowMajorEntries.allSatisfy(\.isFinite) else {
      throw fail(
        "\(path).transforms",
        "the Transform's matrix overflows: its entries are not all finite")
    }
    guard let transform = Transform(matrix: matrix, object: object) else {
      throw fail(
        "\(path).transforms",
        "the Transform's matrix has no inverse (a scale of 0?)")
    }
    if let problem = SceneParser.matrixProblem(transform, options.precision) {
      throw fail("\(path).transforms", problem)
        .exceeding(options.precision)
    }
    if openTransforms == 0
      && !SceneParser.movedGeometryIsFinite(transform, options.precision)
    {
      throw fail(path, SceneParser.movedGeometryMessage(options.precision))
        .exceeding(options.precision)
    }
    return transform
  }

  static let operations = [
    "translate", "scale", "uniformScale", "xRotate", "yRotate", "zRotate",
    "rotate",
  ]

  /// One entry of `transforms`: a name and its numbers, in one string.
  func operation(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> Matrix4<Double> {
    guard case .string(let text) = value else {
      throw fail(path, "expected a string such as \"translate 0 1 0\"")
    }
    let words = text.split(whereSeparator: \.isWhitespace)
    guard let name = words.first.map(String.init),
      Self.operations.contains(name)
    else {
      let word = words.first.map(String.init) ?? ""
      let hint =
        nearest(to: word, in: Self.operations)
        .map { "; did you mean '\($0)'?" } ?? ""
      throw fail(
        path,
        "unknown transform \(quoted(.string(word))); expected one of "
          + Self.operations.joined(separator: ", ") + hint)
    }
    let counts = [
      "translate": 3, "scale": 3, "uniformScale": 1, "xRotate": 1,
      "yRotate": 1, "zRotate": 1, "rotate": 4,
    ]
    let expected = counts[name] ?? 0
    let numbers = try self.numbers(
      words.dropFirst().joined(separator: " "), count: expected, path,
      what: "'\(name)' takes")
    switch name {
    case "translate":
      return .translation(Vector3(numbers[0], numbers[1], numbers[2]))
    case "scale":
      guard numbers.allSatisfy({ $0 != 0 }) else {
        throw fail(path, "'scale' factors must not be 0")
      }
      return .scale(Vector3(numbers[0], numbers[1], numbers[2]))
    case "uniformScale":
      guard numbers[0] != 0 else {
        throw fail(path, "'uniformScale' must not be 0")
      }
      return .uniformScale(numbers[0])
    case "xRotate": return .rotationX(degrees: numbers[0])
    case "yRotate": return .rotationY(degrees: numbers[0])
    case "zRotate": return .rotationZ(degrees: numbers[0])
    default:
      let axis = Vector3(numbers[0], numbers[1], numbers[2])
      guard axis.maxMagnitude > 0 else {
        throw fail(path, "'rotate' needs a non-zero axis")
      }
      return .rotation(axis: axis, degrees: numbers[3])
    }
  }

  func mesh(
    _ fields: [String: PropertyList], _ path: String, material: Int
  ) throws(SceneError) -> SceneObject<Double> {
    let name = try required(string(fields, "objFile", path), "objFile", path)
    let file = try resource(
      name, folder: "Meshes", fileExtension: "obj", "\(path).objFile")
    let textured =
      materials.indices.contains(material)
      && materials[material].texturePath != nil
    let loaded: MeshLoader.Loaded
    do {
      loaded = try MeshLoader.load(
        file, materialIndex: material, textured: textured,
        normals: options.meshNormals, precision: options.precision,
        threads: options.threads, cache: meshCache)
    } catch {
      switch error {
      case .inFile(let inner): throw inner
      case .atReference(let message): throw fail("\(path).objFile", message)
      }
    }
    meshFiles.paths.append(file)
    if textured && !loaded.hasTextureCoordinates {
      throw fail(
        "\(path).objFile",
        "material \(material) has a texture, but the mesh "
          + "'\(SceneParser.escaped(file))' has no texture coordinates "
          + "(no face gives vt)")
    }
    return loaded.object
  }

  /// The material of the object at `path`, as `object` chooses it.
  func own(
    _ fields: [String: PropertyList], _ path: String, _ forced: Int?,
    _ inherited: Int?
  ) throws(SceneError) -> Int {
    if let forced { return forced }
    let own = try materialIndex(fields, path)
    return own ?? inherited ?? 0
  }

  /// A dictionary of `type` NAME for a kind of object the caller added
  /// (`SceneOptions.shapes`): each field a string of its numbers.
  func shape(
    _ kind: ShapeKind, _ fields: [String: PropertyList], _ path: String,
    material: Int
  ) throws(SceneError) -> SceneObject<Double> {
    try checkKeys(
      fields, ["type", "materialIndex"] + kind.fields.map(\.name), path)
    var values: [String: [Double]] = [:]
    for field in kind.fields {
      let value = try required(fields[field.name], field.name, path)
      values[field.name] = try numbers(
        value, count: field.count, "\(path).\(field.name)")
    }
    switch kind.make(values, material) {
    case .success(let shape): return .shape(Shape(shape))
    case .failure(let problem): throw fail(path, problem.message)
    }
  }
}
