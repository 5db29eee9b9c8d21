#if canImport(FoundationEssentials)
  import FoundationEssentials
#else
  import Foundation
#endif

/// Where the course's loader finds a resource it knows by name: a mesh
/// `NAME` is `Meshes/NAME.obj` beside the scene, then `NAME.obj` beside
/// it; a texture `Textures/NAME.bmp`, then `NAME.bmp` (and NAME itself in
/// both places when it already ends in the extension). Property lists
/// name their meshes and textures so; a text scene names a path, and
/// falls back on these when the path names no file.
enum ResourceLookup {
  /// The files `name` may be, in the order they are tried, for a scene
  /// file at `scene`.
  static func candidates(
    _ name: String, folder: String, fileExtension: String,
    besideScene scene: String
  ) -> [String] {
    let base: String
    if let slash = scene.lastIndex(of: "/") {
      base = String(scene[...slash])
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
    return candidates
  }

  /// The first of `candidates` that exists, if any.
  static func existing(_ candidates: [String]) -> String? {
    candidates.first { FileManager.default.fileExists(atPath: $0) }
  }
}
