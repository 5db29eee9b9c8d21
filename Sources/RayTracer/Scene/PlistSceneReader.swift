#if canImport(FoundationEssentials)
  import FoundationEssentials
#else
  import Foundation
#endif

/// Reads the Swift course's property-list scenes into the same model the
/// text format builds:
///
///     Camera      {type PerspectiveCamera, center, direction, up, angle}
///     Lights      [{type PointLight, position, color, [falloff]}
///                  | {type DirectionalLight, direction, color}]
///     Background  {[color], [ambientLight]}
///     Materials   [{[type PhongMaterial], [diffuseColor 1 1 1],
///                   [specularColor 0 0 0], [shininess 0], [texture NAME]}]
///     Group       [object…]
///
/// An object is a dictionary with a `type` and an optional `materialIndex`
/// (default: the enclosing group's, or 0): `Sphere` (center, radius),
/// `Plane` (normal, offset: the plane n·P + offset = 0), `Triangle`
/// (vertex0, vertex1, vertex2), `TriangleMesh` (objFile NAME, the file
/// `Meshes/NAME.obj` beside the scene), `Group` (Group: [object…]) or
/// `Transform` (transforms: ["translate x y z", "scale x y z",
/// "uniformScale s", "xRotate deg", "yRotate deg", "zRotate deg",
/// "rotate ax ay az deg"…], transformed: object, whose material is the
/// Transform's `materialIndex` when it gives one). The matrix is
/// T₁·T₂·…·Tₙ, as the text format's `Transform` composes.
///
/// Every value is a string of numbers separated by spaces ("0 0 10"); a
/// single number may also be a `<real>` or `<integer>`. Unknown keys are
/// errors (with the nearest known key), as are the text format's every
/// limit: non-finite numbers, nesting, zero vectors, negative colours.
/// Every problem is one `SceneError` naming the key path
/// (`Materials[2].diffuseColor: expected 3 numbers, found "0.2 0.8"`).
public enum PlistSceneReader {
  /// Parses the property list in `bytes`; `file` names it in messages and
  /// locates the meshes and textures it names.
  public static func parse(
    bytes: [UInt8], file: String, options: SceneOptions = .init(style: .course)
  ) throws(SceneError) -> Scene {
    let root = try PropertyList.decode(
      bytes, file: SceneParser.escaped(file))
    var builder = PlistSceneBuilder(file: file, options: options)
    return try builder.scene(root)
  }
}

/// The schema's reading of one decoded property list.
struct PlistSceneBuilder {
  let file: String
  let options: SceneOptions
  private var materials: [Material<Double>] = []
  /// Every mesh file read, for `Scene.meshFiles` (a reference: the reader's
  /// methods do not mutate it otherwise).
  private let meshFiles = ReadFiles()
  /// Transforms open at the current object: only the outermost checks the
  /// geometry it moves, as in the text format.
  private var openTransforms = 0

  init(file: String, options: SceneOptions) {
    self.file = file
    self.options = options
  }

  mutating func scene(_ root: PropertyList) throws(SceneError) -> Scene {
    let top = try dictionary(root, "the property list")
    try checkKeys(
      top, ["Camera", "Lights", "Background", "Materials", "Group"], "")
    guard let cameraValue = top["Camera"] else {
      throw fail("", "the scene has no Camera")
    }
    let camera = try self.camera(cameraValue, "Camera")
    var lights: [Light<Double>] = []
    if let value = top["Lights"] {
      for (index, light) in try array(value, "Lights").enumerated() {
        lights.append(try self.light(light, "Lights[\(index)]"))
      }
    }
    var background: RGB<Double> = .zero
    var ambient: RGB<Double>?
    if let value = top["Background"] {
      let fields = try dictionary(value, "Background")
      try checkKeys(fields, ["color", "ambientLight"], "Background")
      background = try color(fields, "color", "Background") ?? .zero
      ambient = try color(fields, "ambientLight", "Background")
    }
    if let value = top["Materials"] {
      for (index, material) in try array(value, "Materials").enumerated() {
        materials.append(try self.material(material, "Materials[\(index)]"))
      }
    }
    guard let groupValue = top["Group"] else {
      throw fail("", "the scene has no Group")
    }
    let root = try group(groupValue, "Group", depth: 1, material: nil)
    var scene = Scene(
      camera: camera, lights: lights, background: background,
      ambient: ambient, materials: materials, root: root)
    scene.meshFiles = meshFiles.paths
    return scene
  }

  // MARK: - Blocks

  private func camera(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> PerspectiveCamera<Double> {
    let fields = try dictionary(value, path)
    try checkKeys(fields, ["type", "center", "direction", "up", "angle"], path)
    try checkType(fields, ["PerspectiveCamera"], path, required: false)
    let center = try required(vector(fields, "center", path), "center", path)
    let direction = try required(
      vector(fields, "direction", path), "direction", path)
    let up = try required(vector(fields, "up", path), "up", path)
    let angle = try required(number(fields, "angle", path), "angle", path)
    guard angle > 0 && angle < 180 else {
      throw fail(
        "\(path).angle",
        "the camera's angle must be between 0 and 180 degrees, found "
          + quoted(fields["angle"]))
    }
    guard direction.maxMagnitude > 0 else {
      throw fail("\(path).direction", "the camera's direction must not be zero")
    }
    guard
      let camera = PerspectiveCamera(
        center: center, direction: direction, up: up, angle: angle)
    else {
      throw fail(
        "\(path).up",
        "the camera's up vector must not be zero or parallel to its direction")
    }
    return camera
  }

  private func light(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> Light<Double> {
    let fields = try dictionary(value, path)
    let type = try checkType(
      fields, ["PointLight", "DirectionalLight"], path, required: true)
    let color = try required(
      self.color(fields, "color", path), "color", path)
    if type == "PointLight" {
      try checkKeys(fields, ["type", "position", "color", "falloff"], path)
      let position = try required(
        vector(fields, "position", path), "position", path)
      let falloff = try number(fields, "falloff", path)
      if let falloff, !(falloff > 0) {
        throw fail(
          "\(path).falloff",
          "'falloff' must be positive, found \(quoted(fields["falloff"]))")
      }
      return .point(position: position, color: color, falloff: falloff)
    }
    try checkKeys(fields, ["type", "direction", "color"], path)
    let direction = try required(
      vector(fields, "direction", path), "direction", path)
    guard direction.maxMagnitude > 0 else {
      throw fail("\(path).direction", "'direction' must not be the zero vector")
    }
    return .directional(direction: direction.normalized(), color: color)
  }

  private func material(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> Material<Double> {
    let fields = try dictionary(value, path)
    try checkKeys(
      fields,
      ["type", "diffuseColor", "specularColor", "shininess", "texture"], path)
    try checkType(fields, ["PhongMaterial", "Material"], path, required: false)
    let shininess = try number(fields, "shininess", path) ?? 0
    guard shininess >= 0 else {
      throw fail(
        "\(path).shininess",
        "'shininess' must not be negative, found \(quoted(fields["shininess"]))"
      )
    }
    var texture: String?
    if let name = try string(fields, "texture", path) {
      texture = try resource(
        name, folder: "Textures", fileExtension: "bmp", "\(path).texture")
    }
    return Material(
      diffuse: try color(fields, "diffuseColor", path) ?? Vector3(1, 1, 1),
      specular: try color(fields, "specularColor", path) ?? .zero,
      shininess: shininess, texturePath: texture)
  }

  // MARK: - Objects

  private mutating func group(
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
  private mutating func object(
    _ value: PropertyList, _ path: String, depth: Int, inherited: Int?,
    forced: Int? = nil
  ) throws(SceneError) -> SceneObject<Double> {
    let fields = try dictionary(value, path)
    let type = try checkType(fields, Self.objectTypes, path, required: true)
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

  private mutating func transform(
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
    if openTransforms == 0
      && !SceneParser.movedGeometryIsFinite(transform)
    {
      throw fail(path, SceneParser.movedGeometryMessage)
    }
    return transform
  }

  static let operations = [
    "translate", "scale", "uniformScale", "xRotate", "yRotate", "zRotate",
    "rotate",
  ]

  /// One entry of `transforms`: a name and its numbers, in one string.
  private func operation(
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

  private func mesh(
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
        normals: options.meshNormals)
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

  // MARK: - Values

  /// The file a resource NAME names, as the course's loader finds it:
  /// `FOLDER/NAME.EXT` beside the scene, then `NAME.EXT` beside it (and
  /// NAME itself in both places when it already ends in .EXT).
  private func resource(
    _ name: String, folder: String, fileExtension: String, _ path: String
  ) throws(SceneError) -> String {
    let base: String
    if let slash = file.lastIndex(of: "/") {
      base = String(file[...slash])
    } else {
      base = ""
    }
    var names = [name + "." + fileExtension]
    if name.hasSuffix("." + fileExtension) { names.insert(name, at: 0) }
    var candidates: [String] = []
    for name in names {
      candidates.append(name.hasPrefix("/") ? name : base + folder + "/" + name)
    }
    for name in names where !name.hasPrefix("/") {
      candidates.append(base + name)
    }
    for candidate in candidates
    where FileManager.default.fileExists(atPath: candidate) {
      return candidate
    }
    throw fail(
      path,
      "no file for \(quoted(.string(name))); tried "
        + candidates.map { "'\(SceneParser.escaped($0))'" }
        .joined(separator: ", "))
  }

  private func materialIndex(
    _ fields: [String: PropertyList], _ path: String
  ) throws(SceneError) -> Int? {
    guard let index = try number(fields, "materialIndex", path) else {
      return nil
    }
    let available = max(materials.count, 1)
    guard index >= 0, index == index.rounded(), index < Double(available)
    else {
      throw fail(
        "\(path).materialIndex",
        "materialIndex \(quoted(fields["materialIndex"])) is out of range: "
          + (materials.isEmpty
            ? "the scene has no materials (only the default, 0)"
            : "the scene has \(materials.count) material"
              + "\(materials.count == 1 ? "" : "s") (0 to \(materials.count - 1))")
      )
    }
    return Int(index)
  }

  private func checkDepth(_ depth: Int, _ path: String) throws(SceneError) {
    guard depth < SceneParser.maximumGroupDepth else {
      throw fail(
        path,
        "Groups and Transforms are nested more than "
          + "\(SceneParser.maximumGroupDepth) deep")
    }
  }

  /// The `type` string, which must be one of `choices` (or absent when not
  /// `required`, giving the first choice).
  @discardableResult
  private func checkType(
    _ fields: [String: PropertyList], _ choices: [String], _ path: String,
    required: Bool
  ) throws(SceneError) -> String {
    guard let type = try string(fields, "type", path) else {
      if required {
        throw fail(
          path,
          "missing 'type' (one of \(choices.joined(separator: ", ")))")
      }
      return choices[0]
    }
    guard choices.contains(type) else {
      let hint =
        nearest(to: type, in: choices)
        .map { "; did you mean '\($0)'?" } ?? ""
      throw fail(
        "\(path).type",
        "unknown type \(quoted(.string(type))); expected "
          + choices.joined(separator: ", ") + hint)
    }
    return type
  }

  private func checkKeys(
    _ fields: [String: PropertyList], _ allowed: [String], _ path: String
  ) throws(SceneError) {
    for key in fields.keys.sorted() where !allowed.contains(key) {
      let hint =
        nearest(to: key, in: allowed)
        .map { "; did you mean '\($0)'?" } ?? ""
      throw fail(
        path.isEmpty
          ? SceneParser.escaped(key) : "\(path).\(SceneParser.escaped(key))",
        "unknown key; expected "
          + allowed.joined(separator: ", ") + hint)
    }
  }

  private func dictionary(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> [String: PropertyList] {
    guard case .dictionary(let fields) = value else {
      throw fail(path, "expected a dictionary, found \(kind(value))")
    }
    return fields
  }

  private func array(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> [PropertyList] {
    guard case .array(let items) = value else {
      throw fail(path, "expected an array, found \(kind(value))")
    }
    return items
  }

  private func string(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> String? {
    guard let value = fields[key] else { return nil }
    guard case .string(let text) = value, !text.isEmpty else {
      throw fail("\(path).\(key)", "expected a name, found \(quoted(value))")
    }
    return text
  }

  private func number(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> Double? {
    guard let value = fields[key] else { return nil }
    if case .number(let number) = value {
      guard number.isFinite else {
        throw fail("\(path).\(key)", "expected a finite number")
      }
      return number
    }
    return try numbers(value, count: 1, "\(path).\(key)")[0]
  }

  private func vector(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> Vector3<Double>? {
    guard let value = fields[key] else { return nil }
    let numbers = try self.numbers(value, count: 3, "\(path).\(key)")
    return Vector3(numbers[0], numbers[1], numbers[2])
  }

  private func color(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> RGB<Double>? {
    guard let value = try vector(fields, key, path) else { return nil }
    guard value.x >= 0 && value.y >= 0 && value.z >= 0 else {
      throw fail("\(path).\(key)", "'\(key)' components must not be negative")
    }
    return value
  }

  private func numbers(
    _ value: PropertyList, count: Int, _ path: String
  ) throws(SceneError) -> [Double] {
    guard case .string(let text) = value else {
      if count == 1, case .number(let number) = value, number.isFinite {
        return [number]
      }
      throw fail(
        path,
        "expected \(count == 1 ? "a number" : "\(count) numbers") in a "
          + "string, found \(quoted(value))")
    }
    return try numbers(text, count: count, path, what: "expected")
  }

  /// Exactly `count` finite decimal numbers separated by blanks, each read
  /// as the text format reads numbers (correctly rounded).
  private func numbers(
    _ text: String, count: Int, _ path: String, what: String
  ) throws(SceneError) -> [Double] {
    let words = text.split(whereSeparator: \.isWhitespace)
    var values: [Double] = []
    for word in words {
      var utf8 = Array(word.utf8)
      let value = utf8.withUnsafeMutableBufferPointer {
        DecimalParser.parse(UnsafeBufferPointer($0))
      }
      guard let value, value.isFinite else { values = []; break }
      values.append(value)
    }
    guard values.count == count, words.count == count else {
      let noun = count == 1 ? "1 number" : "\(count) numbers"
      let found =
        words.count == values.count || values.isEmpty && words.isEmpty
        ? "" : " (finite, decimal)"
      throw fail(
        path, "\(what) \(noun)\(found), found \(quoted(.string(text)))")
    }
    return values
  }

  private func required<T>(
    _ value: T?, _ key: String, _ path: String
  ) throws(SceneError) -> T {
    guard let value else {
      throw fail(path, "missing '\(key)'")
    }
    return value
  }

  private func kind(_ value: PropertyList) -> String {
    switch value {
    case .string(let text): "the string \(quoted(.string(text)))"
    case .number: "a number"
    case .boolean: "a boolean"
    case .array: "an array"
    case .dictionary: "a dictionary"
    case .other: "data or a date"
    }
  }

  /// A value as a message quotes it: strings in double quotes, escaped and
  /// cut to 48 characters.
  private func quoted(_ value: PropertyList?) -> String {
    guard let value else { return "nothing" }
    switch value {
    case .string(let text):
      let cut = text.count > 48 ? String(text.prefix(48)) + "…" : text
      return "\"\(SceneParser.escaped(cut))\""
    case .number(let number): return "\(number)"
    default: return kind(value)
    }
  }

  private func fail(_ path: String, _ message: String) -> SceneError {
    SceneError(
      file: SceneParser.escaped(file), line: 0, column: 0,
      message: path.isEmpty ? message : "\(path): \(message)")
  }
}

/// The files a reader opened, collected as it goes.
private final class ReadFiles {
  var paths: [String] = []
}
