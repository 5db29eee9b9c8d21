import Geometry
import SceneDescription

/// The text format's Lights, Background and Materials blocks.
extension SceneParser {
  mutating func parseLights() throws(SceneError) -> [Light<Double>] {
    try parseCountedBlock(
      "Lights", count: "numLights", noun: "light",
      choices: ["PointLight", "DirectionalLight"]
    ) { (parser: inout SceneParser, name: String) throws(SceneError) in
      name == "PointLight"
        ? try parser.parsePointLight() : try parser.parseDirectionalLight()
    }
  }

  mutating func parsePointLight() throws(SceneError) -> Light<Double> {
    var position: Vector3<Double>?
    var color: RGB<Double>?
    var falloff: Double?
    let close = try parseFields(
      "PointLight", ["position", "color", "falloff"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "position": position = try parser.vector()
      case "color": color = try parser.color(field)
      default: falloff = try parser.positive(field)
      }
    }
    guard let position, let color else {
      throw missing(
        "PointLight", [("position", position != nil), ("color", color != nil)],
        close)
    }
    return .point(position: position, color: color, falloff: falloff)
  }

  mutating func parseDirectionalLight() throws(SceneError) -> Light<
    Double
  > {
    var direction: Vector3<Double>?
    var color: RGB<Double>?
    let close = try parseFields(
      "DirectionalLight", ["direction", "color"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "direction": direction = try parser.nonZeroVector(field)
      default: color = try parser.color(field)
      }
    }
    guard let direction, let color else {
      throw missing(
        "DirectionalLight",
        [("direction", direction != nil), ("color", color != nil)],
        close)
    }
    return .directional(direction: direction.normalized(), color: color)
  }

  mutating func parseBackground() throws(SceneError) -> (
    color: RGB<Double>?, ambient: RGB<Double>?
  ) {
    var color: RGB<Double>?
    var ambient: RGB<Double>?
    _ = try parseFields(
      "Background", ["color", "ambientLight", "cubeMap"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "color": color = try parser.color(field)
      case "ambientLight": ambient = try parser.color(field)
      default:
        // An environment map for reflected rays, which a ray caster never
        // traces: accepted so that the course's scenes load, and ignored
        // (misses show the background colour).
        let path = try parser.next()
        guard path.kind == .word else {
          throw parser.error(
            at: path, "expected the cube map's path after 'cubeMap'")
        }
      }
    }
    return (color, ambient)
  }

  mutating func parseMaterials() throws(SceneError) -> [Material<
    Double
  >] {
    try parseCountedBlock(
      "Materials", count: "numMaterials", noun: "material",
      choices: ["Material", "PhongMaterial"]
    ) { (parser: inout SceneParser, name: String) throws(SceneError) in
      try parser.parseMaterial(name)
    }
  }

  mutating func parseMaterial(_ name: String) throws(SceneError)
    -> Material<Double>
  {
    var diffuse: RGB<Double>?
    var specular: RGB<Double>?
    var shininess: Double?
    var texture: String?
    let close = try parseFields(
      name, ["diffuseColor", "specularColor", "shininess", "texture"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "diffuseColor": diffuse = try parser.color(field)
      case "specularColor": specular = try parser.color(field)
      case "texture":
        texture = parser.resolved(
          try parser.path(after: field).0, folder: "Textures",
          fileExtension: "bmp")
      default: shininess = try parser.nonNegative(field)
      }
    }
    guard let diffuse else {
      throw missing(name, [("diffuseColor", false)], close)
    }
    return Material(
      diffuse: diffuse, specular: specular ?? .zero, shininess: shininess ?? 0,
      texturePath: texture)
  }
}
