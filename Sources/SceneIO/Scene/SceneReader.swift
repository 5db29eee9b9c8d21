import Geometry
import SceneDescription

/// Reads a scene file in either format, recognised by its content: a
/// property list (XML or binary, the Swift course's files; see
/// `PlistSceneReader`) or the text format of the original assignment (see
/// `SceneParser`), whatever the file's name.
package enum SceneReader {
  /// The scene in the file at `path`; meshes read as `options` says.
  package static func read(
    contentsOf path: String, options: SceneOptions
  ) throws(SceneError) -> Scene {
    let bytes: SceneBytes
    do {
      bytes = try SceneBytes.contentsOf(path, threads: options.threads)
    } catch {
      throw SceneError(
        file: SceneParser.escaped(path), line: 0, column: 0,
        message: error.reason)
    }
    if PropertyList.recognises(bytes.buffer) {
      return try PlistSceneReader.parse(
        bytes: Array(bytes.buffer), file: path, options: options)
    }
    var parser = SceneParser(bytes: bytes, file: path, options: options)
    return try parser.parseScene()
  }

  /// The scene in `bytes`, named `file` in messages (and locating its
  /// meshes and textures).
  package static func parse(
    bytes: [UInt8], file: String, options: SceneOptions = .init(style: .course)
  ) throws(SceneError) -> Scene {
    let recognised = bytes.withUnsafeBufferPointer {
      PropertyList.recognises($0)
    }
    if recognised {
      return try PlistSceneReader.parse(
        bytes: bytes, file: file, options: options)
    }
    return try SceneParser.parse(bytes: bytes, file: file, options: options)
  }
}
