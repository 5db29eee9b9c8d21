/// Whether two paths name one file, by identity rather than spelling.
package enum FileIdentity {
  /// True when both files exist and are the same file (device and inode:
  /// hard links and symbolic links included), or when neither exists and
  /// both name the same entry of the same folder once the folders are
  /// resolved (`./a.png` and `a.png`). A file that exists and one that
  /// does not are different.
  package static func same(_ first: String, _ second: String) -> Bool {
    var a = stat()
    var b = stat()
    let firstExists = stat(first, &a) == 0
    let secondExists = stat(second, &b) == 0
    if firstExists && secondExists {
      return a.st_dev == b.st_dev && a.st_ino == b.st_ino
    }
    if firstExists || secondExists { return false }
    guard let resolvedFirst = entry(first), let resolvedSecond = entry(second)
    else { return first == second }
    return resolvedFirst == resolvedSecond
  }

  /// The path's folder, resolved, and its last component; nil when the
  /// folder cannot be resolved.
  static func entry(_ path: String) -> String? {
    let slash = path.lastIndex(of: "/")
    let folder = slash.map { String(path[...$0]) } ?? "."
    let name = slash.map { String(path[path.index(after: $0)...]) } ?? path
    guard let resolved = realpath(folder.isEmpty ? "/" : folder, nil) else {
      return nil
    }
    defer { free(resolved) }
    return String(cString: resolved) + "/" + name
  }

  /// A file's identity (device and inode), for keying what was read from
  /// it; nil when it does not exist.
  package struct Key: Hashable, Sendable {
    var device: UInt64
    var inode: UInt64
  }

  package static func key(_ path: String) -> Key? {
    var status = stat()
    guard stat(path, &status) == 0 else { return nil }
    return Key(
      device: UInt64(truncatingIfNeeded: status.st_dev),
      inode: UInt64(truncatingIfNeeded: status.st_ino))
  }
}
