// The C library, for every file of the package: the one place that names
// its module. Darwin and Glibc declare the POSIX calls used here (open,
// pread, write, rename, sigaction, sysconf, clock_gettime …) with the same
// names and types; where they differ, the difference is wrapped in this
// folder (see `Platform`).
#if canImport(Darwin)
  @_exported import Darwin
#elseif canImport(Glibc)
  @_exported import Glibc
#else
  #error("raytrace builds on macOS (Darwin) and Linux (Glibc)")
#endif

/// What differs between macOS and Linux, behind one name.
package enum Platform {
  /// The longest file name `folder`'s file system accepts, or nil when it
  /// does not say (pathconf's _PC_NAME_MAX, 255 on most).
  package static func nameLimit(inFolder folder: String) -> Int? {
    let limit = pathconf(folder, Int32(_PC_NAME_MAX))
    return limit > 0 ? limit : nil
  }

  /// The bytes an unprivileged process may still write on the file system
  /// that holds `folder`, or nil when it does not say.
  package static func freeBytes(inFolder folder: String) -> Int? {
    var status = statvfs()
    guard statvfs(folder, &status) == 0 else { return nil }
    let (bytes, overflow) = Int(status.f_bavail).multipliedReportingOverflow(
      by: Int(status.f_frsize))
    return overflow ? nil : bytes
  }

  /// PATH_MAX: the longest path a system call accepts, its final NUL
  /// included (4096 on Linux, 1024 on macOS).
  package static let pathLimit = Int(PATH_MAX)

  /// Clears O_NONBLOCK on an open descriptor, so that writes wait.
  package static func setBlocking(_ descriptor: Int32) {
    let flags = fcntl(descriptor, F_GETFL)
    if flags >= 0 { _ = fcntl(descriptor, F_SETFL, flags & ~O_NONBLOCK) }
  }

  /// Ignores `signalNumber` and says whether it was ignored already (as a
  /// process started by `nohup` finds SIGHUP). The handler's type differs
  /// (`sig_t`, `__sighandler_t`); SIG_IGN is the same pointer value on both.
  package static func ignoreReportingWhetherIgnored(_ signalNumber: Int32)
    -> Bool
  {
    let previous = signal(signalNumber, SIG_IGN)
    return unsafeBitCast(previous, to: Int.self)
      == unsafeBitCast(SIG_IGN, to: Int.self)
  }

  /// The process's environment, for `posix_spawn`.
  static var environment: UnsafeMutablePointer<UnsafeMutablePointer<CChar>?>? {
    #if canImport(Darwin)
      return _NSGetEnviron().pointee
    #else
      return environ
    #endif
  }

  /// The peak resident memory of a finished child, in bytes: `ru_maxrss`
  /// is in bytes on macOS and in KiB on Linux.
  package static func peakBytes(_ usage: rusage) -> Int {
    #if canImport(Darwin)
      return Int(usage.ru_maxrss)
    #else
      return Int(usage.ru_maxrss) * 1024
    #endif
  }

  /// The path of the running executable, or nil when the system does not
  /// say.
  package static func currentExecutable() -> String? {
    #if canImport(Darwin)
      var size: UInt32 = 0
      _ = _NSGetExecutablePath(nil, &size)
      var buffer = [CChar](repeating: 0, count: Int(size) + 1)
      guard _NSGetExecutablePath(&buffer, &size) == 0 else { return nil }
      return String(cString: buffer)
    #else
      var buffer = [CChar](repeating: 0, count: 4096)
      let length = readlink("/proc/self/exe", &buffer, buffer.count - 1)
      guard length > 0 else { return nil }
      return String(
        decoding: buffer[0..<length].map { UInt8(bitPattern: $0) },
        as: UTF8.self)
    #endif
  }

  /// Writes all of `bytes` to `descriptor` with write(2), again after an
  /// interruption: nil when every byte is written, otherwise why not (the
  /// C library's words for `errno`, or "nothing written" when a write
  /// wrote nothing, rather than trying forever).
  package static func writeAll(_ descriptor: Int32, _ bytes: [UInt8])
    -> String?
  {
    var written = 0
    while written < bytes.count {
      let result = bytes[written...].withUnsafeBytes {
        write(descriptor, $0.baseAddress, $0.count)
      }
      if result < 0 && errno == EINTR { continue }
      guard result > 0 else {
        return result < 0 ? String(cString: strerror(errno)) : "nothing written"
      }
      written += result
    }
    return nil
  }

  /// The names in `folder` (files and folders, not `.` and `..`), sorted;
  /// empty when the folder cannot be read.
  package static func names(in folder: String) -> [String] {
    guard let directory = opendir(folder) else { return [] }
    defer { closedir(directory) }
    var names: [String] = []
    while let entry = readdir(directory) {
      let name = withUnsafeBytes(of: entry.pointee.d_name) { raw in
        String(decoding: raw.prefix { $0 != 0 }, as: UTF8.self)
      }
      if name != "." && name != ".." { names.append(name) }
    }
    return names.sorted()
  }

  /// A new pipe's two descriptors (read, write), or nil.
  package static func makePipe() -> (read: Int32, write: Int32)? {
    var ends: [Int32] = [0, 0]
    guard pipe(&ends) == 0 else { return nil }
    return (ends[0], ends[1])
  }

  /// `rename(2)`: 0, or −1 with `errno` set.
  package static func renameFile(_ from: String, _ to: String) -> Int32 {
    rename(from, to)
  }

  /// `link(2)`: 0, or −1 with `errno` set.
  package static func linkFile(_ existing: String, _ new: String) -> Int32 {
    link(existing, new)
  }
}

extension Platform {
  /// The number of processors online, the default thread count.
  package static var availableCores: Int {
    max(1, Int(sysconf(Int32(_SC_NPROCESSORS_ONLN))))
  }
}
