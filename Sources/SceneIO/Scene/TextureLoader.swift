import Geometry
import SceneDescription
import PlatformSupport

/// Reads the textures a scene's materials name, for a shaded render: the
/// only render that needs them, so depth and normals images never open a
/// texture file.
package enum TextureLoader {
  /// Per material of `scene`, its texture, or nil for an untextured one;
  /// each file is read once however many materials name it.
  ///
  /// - Throws: `SceneError` naming the file (line 0) when a texture cannot
  ///   be read or is not a BMP this renderer reads.
  package static func load(for scene: Scene) throws(SceneError) -> [Texture?] {
    var cache: [String: Texture] = [:]
    var textures: [Texture?] = []
    for material in scene.materials {
      guard let path = material.texturePath else {
        textures.append(nil)
        continue
      }
      if let texture = cache[path] {
        textures.append(texture)
        continue
      }
      let texture = try read(path)
      cache[path] = texture
      textures.append(texture)
    }
    return textures
  }

  /// The texture in the BMP file at `path`.
  package static func read(_ path: String) throws(SceneError) -> Texture {
    let file = SceneParser.escaped(path)
    if let problem = MemoryNeed.problem(reading: path, perByte: 2) {
      throw SceneError(file: file, line: 0, column: 0, message: problem)
    }
    let bytes: [UInt8]
    do {
      bytes = try readFile(path)
    } catch {
      throw SceneError(
        file: file, line: 0, column: 0,
        message: "cannot read the texture: \(error.reason)")
    }
    do {
      return Texture(image: try BMPReader.decode(bytes))
    } catch {
      throw SceneError(
        file: file, line: 0, column: 0, message: error.description)
    }
  }
}
