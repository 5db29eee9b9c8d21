import Geometry
import SceneDescription
import PlatformSupport

/// Files whose contents are estimated before they are read: a mesh or a
/// texture that could not fit in what the process may use is refused in
/// one line, not by an abort part way through reading it.
enum MemoryNeed {
  /// Bytes a file of `size` takes once read, at most: an OBJ mesh's arrays
  /// (positions, normals and indices in Double and Int32, its normals
  /// smoothed) take up to 6 bytes per byte of text; a BMP texture about
  /// its own size.
  static func estimate(fileSize size: Int, perByte: Int) -> Int {
    size.multipliedReportingOverflow(by: perByte).overflow
      ? Int.max : size * perByte
  }

  /// Why reading `path` as something that takes `perByte` bytes per byte
  /// of the file does not fit, or nil (also when the file's size cannot be
  /// known: reading it then says why).
  static func problem(reading path: String, perByte: Int) -> String? {
    var status = stat()
    guard stat(path, &status) == 0, let limit = Memory.limits().first else {
      return nil
    }
    let need = estimate(fileSize: Int(status.st_size), perByte: perByte)
    guard need > limit.bytes else { return nil }
    let gib = { (bytes: Int) in
      "\(Double(bytes / 1_048_576) / 1024) GiB"
    }
    return "'\(SceneParser.escaped(path))' would need about \(gib(need)) "
      + "once read, and the process may use at most \(gib(limit.bytes)) "
      + "(\(limit.what))"
  }
}
