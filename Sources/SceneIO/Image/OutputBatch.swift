import Geometry
import SceneDescription
import PlatformSupport

/// The files one run writes, replaced all together or not at all.
///
/// Made before rendering: each target is checked (not a folder, its folder
/// writable) by creating its temporary file beside it, which then exists,
/// empty, for the whole render; a terminating signal removes it. `commit`
/// writes every temporary in full, then for each target keeps a hard link
/// to the old file (if any) and renames the temporary over it. If a rename
/// fails part way, the targets already replaced are put back from their
/// links (or removed, if they were new), and the error names the file that
/// failed. A signal that arrives during the renames does the same from
/// its handler (`PendingFiles`). What remains: POSIX renames one file at a
/// time, so another process can see some targets replaced and others not
/// for the microseconds between the renames, and a crash of the machine in
/// that window can leave a mixed set.
package final class OutputBatch {
  /// The system calls a batch makes to replace its targets, replaceable in
  /// tests to make one fail.
  package struct FileOperations: Sendable {
    package var rename: @Sendable (String, String) -> Int32
    package var link: @Sendable (String, String) -> Int32

    package static let system = FileOperations(
      rename: { Platform.renameFile($0, $1) },
      link: { Platform.linkFile($0, $1) })
  }

  package let paths: [String]
  /// Per path, its temporary file, or nil for a target written in place
  /// (a FIFO or a character device, which is never replaced).
  private var temporaries: [String?] = []
  private var descriptors: [Int32] = []
  private let operations: FileOperations
  private var finished = false

  /// Creates the temporary file of every path.
  ///
  /// - Throws: `OutputError` naming the first path that cannot be written
  ///   (a folder, a missing or read-only folder, too many outputs), after
  ///   removing the temporaries already made.
  package init(
    paths: [String], operations: FileOperations = .system
  ) throws(OutputError) {
    PendingFiles.installHandlers()
    self.paths = paths
    self.operations = operations
    for path in paths {
      do throws(OutputError) {
        if let descriptor = try Self.openInPlace(path) {
          temporaries.append(nil)
          descriptors.append(descriptor)
          continue
        }
        try Self.checkReplaceable(path)
      } catch {
        abandon()
        throw error
      }
      // A fresh random name each try: a name another run holds (or left
      // behind) fails O_EXCL and the next try takes another.
      var temporary = ""
      var descriptor: Int32 = -1
      for _ in 0..<Self.tries {
        temporary = Self.temporaryPath(for: path)
        guard PendingFiles.add(.remove, temporary) else {
          abandon()
          throw OutputError(path: path, reason: "too many outputs at once")
        }
        descriptor = open(temporary, O_WRONLY | O_CREAT | O_EXCL, 0o644)
        if descriptor >= 0 { break }
        let failure = errno
        PendingFiles.remove(temporary)
        guard failure == EEXIST else {
          errno = failure
          break
        }
      }
      guard descriptor >= 0 else {
        let reason = Self.systemReason()
        abandon()
        throw OutputError(path: path, reason: reason)
      }
      temporaries.append(temporary)
      descriptors.append(descriptor)
    }
  }

  /// A target that is not a regular file: a FIFO or a character device
  /// (`/dev/null`, a terminal) is written in place, opened now (a FIFO
  /// only when a reader is waiting, so that nothing blocks); a directory,
  /// socket or block device is refused. Nil for a regular file or none.
  static func openInPlace(_ path: String) throws(OutputError) -> Int32? {
    var status = stat()
    guard stat(path, &status) == 0 else { return nil }
    switch status.st_mode & S_IFMT {
    case S_IFREG: return nil
    case S_IFDIR: throw OutputError(path: path, reason: "it is a directory")
    case S_IFIFO, S_IFCHR:
      let descriptor = open(path, O_WRONLY | O_NONBLOCK | O_CLOEXEC)
      guard descriptor >= 0 else {
        throw OutputError(
          path: path,
          reason: errno == ENXIO
            ? "it is a FIFO with no reader" : systemReason())
      }
      Platform.setBlocking(descriptor)
      return descriptor
    case S_IFSOCK:
      throw OutputError(path: path, reason: "it is a socket")
    default:
      throw OutputError(
        path: path, reason: "it is a device that is not written as a file")
    }
  }

  /// What the final rename could refuse, checked before any work: a name
  /// longer than its folder allows, a path longer than the system's, and a
  /// file in a sticky folder (/tmp) that belongs to another user.
  static func checkReplaceable(_ path: String) throws(OutputError) {
    let slash = path.lastIndex(of: "/")
    let folder =
      slash.map { $0 == path.startIndex ? "/" : String(path[..<$0]) }
      ?? "."
    let name = slash.map { String(path[path.index(after: $0)...]) } ?? path
    let limit = Platform.nameLimit(inFolder: folder)
    if let limit, name.utf8.count > limit {
      throw OutputError(
        path: path,
        reason: "its name is \(name.utf8.count) bytes long, and the folder "
          + "allows at most \(limit)")
    }
    if path.utf8.count >= Platform.pathLimit {
      throw OutputError(
        path: path,
        reason: "the path is \(path.utf8.count) bytes long, and the system "
          + "allows at most \(Platform.pathLimit - 1)")
    }
    var target = stat()
    var parent = stat()
    guard stat(path, &target) == 0, stat(folder, &parent) == 0,
      parent.st_mode & S_ISVTX != 0
    else { return }
    let user = geteuid()
    if user != 0 && target.st_uid != user && parent.st_uid != user {
      throw OutputError(
        path: path,
        reason: "it belongs to another user, in a folder where only a "
          + "file's owner may replace it (sticky)")
    }
  }

  deinit { abandon() }

  /// Removes every temporary; the targets are left as they were.
  package func abandon() {
    guard !finished else { return }
    finished = true
    for (temporary, descriptor) in zip(temporaries, descriptors) {
      close(descriptor)
      guard let temporary else { continue }
      unlink(temporary)
      PendingFiles.remove(temporary)
    }
  }

  /// Writes `contents[i]` to `paths[i]` for every i, all or none.
  package func commit(_ contents: [[UInt8]]) throws(OutputError) {
    precondition(contents.count == paths.count && !finished)
    for index in paths.indices {
      do throws(OutputError) {
        try Self.writeWhole(
          contents[index], to: descriptors[index], reportingAs: paths[index])
      } catch {
        abandon()
        throw error
      }
    }
    for descriptor in descriptors { close(descriptor) }
    descriptors = []
    // Old targets kept aside (hard links), so that a failure part way can
    // put them back.
    var replaced: [Replacement] = []
    defer { forget(replaced) }
    for (index, target) in paths.enumerated() {
      // Written in place: nothing to rename.
      guard let temporary = temporaries[index] else { continue }
      let entry = keepAside(target)
      replaced.append(entry)
      guard operations.rename(temporary, target) == 0 else {
        let reason = Self.systemReason()
        undo(replaced.dropLast(), from: index)
        throw OutputError(path: target, reason: reason)
      }
      PendingFiles.remove(temporary)
    }
    finished = true
  }

  /// A target about to be replaced: a hard link to its old file, or
  /// whether there was none.
  private struct Replacement {
    var target: String
    var backup: String?
    var existed: Bool
  }

  /// Links the target's old file aside and records how a signal handler
  /// would undo its replacement. A file system without hard links (FAT,
  /// exFAT) leaves no backup: that one target cannot be put back.
  private func keepAside(_ target: String) -> Replacement {
    for _ in 0..<Self.tries {
      let backup = Self.temporaryPath(for: target)
      if operations.link(target, backup) == 0 {
        if PendingFiles.add(.restore, backup, target) {
          return Replacement(target: target, backup: backup, existed: true)
        }
        unlink(backup)
        break
      }
      // Only a name already taken is worth another try.
      if errno != EEXIST { break }
    }
    let existed = access(target, F_OK) == 0
    if !existed { _ = PendingFiles.add(.remove, target) }
    return Replacement(target: target, backup: nil, existed: existed)
  }

  /// Drops the backups once they are no longer needed.
  private func forget(_ replaced: [Replacement]) {
    for entry in replaced {
      if let backup = entry.backup {
        PendingFiles.remove(backup)
        unlink(backup)
      } else if !entry.existed {
        PendingFiles.remove(entry.target)
      }
    }
  }

  /// Puts back every target in `replaced` and removes the temporaries from
  /// `index` on.
  private func undo(_ replaced: ArraySlice<Replacement>, from index: Int) {
    for entry in replaced {
      if let backup = entry.backup {
        _ = operations.rename(backup, entry.target)
      } else if !entry.existed {
        unlink(entry.target)
      }
    }
    for case let temporary? in temporaries[index...] {
      unlink(temporary)
      PendingFiles.remove(temporary)
    }
    finished = true
  }

  private static func writeWhole(
    _ bytes: [UInt8], to descriptor: Int32, reportingAs path: String
  ) throws(OutputError) {
    if let reason = Platform.writeAll(descriptor, bytes) {
      throw OutputError(path: path, reason: reason)
    }
  }

  /// `.rt-` and 16 random hexadecimal digits, `.tmp`, in the target's
  /// folder: within one file system for the rename, short enough for any
  /// name the folder accepts, and a name no other run holds (64 random
  /// bits; a collision only costs another try, as it is created
  /// exclusively). docs/ROBUSTNESS.md says how leftovers are removed.
  static func temporaryPath(for path: String) -> String {
    let slash = path.lastIndex(of: "/")
    let folder = slash.map { String(path[...$0]) } ?? ""
    let random = String(UInt64.random(in: 0...UInt64.max), radix: 16)
    let digits = String(repeating: "0", count: 16 - random.count) + random
    return "\(folder).rt-\(digits).tmp"
  }

  /// Names tried before giving up on a folder.
  static let tries = 8

  static func systemReason() -> String {
    String(cString: strerror(errno))
  }
}
