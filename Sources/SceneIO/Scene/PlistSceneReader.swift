import Geometry
import SceneDescription
import PlatformSupport

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
package enum PlistSceneReader {
  /// Parses the property list in `bytes`; `file` names it in messages and
  /// locates the meshes and textures it names.
  package static func parse(
    bytes: [UInt8], file: String, options: SceneOptions = .init(style: .course)
  ) throws(SceneError) -> Scene {
    if let problem = options.shapeNameProblem() {
      throw SceneError(file: file, line: 0, column: 0, message: problem)
    }
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
  var materials: [Material<Double>] = []
  /// Every mesh file read, for `Scene.meshFiles` (a reference: the reader's
  /// methods do not mutate it otherwise).
  let meshFiles = ReadFiles()
  /// Each mesh file read once, however often the scene names it.
  let meshCache = MeshLoader.Cache()
  /// Transforms open at the current object: only the outermost checks the
  /// geometry it moves, as in the text format.
  var openTransforms = 0

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

  func camera(
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

  func light(
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

  func material(
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
}

/// The files a reader opened, collected as it goes.
final class ReadFiles {
  var paths: [String] = []
}
