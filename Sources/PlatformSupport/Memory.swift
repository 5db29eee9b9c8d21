/// Large arrays on 2 MiB pages: a 4 KiB page fault for every 4 KiB of the
/// arrays of a million spheres, or of a render's buffers, was a tenth to a
/// quarter of the step that first wrote them.
package enum Memory {
  /// Asks the kernel to back `buffer` with 2 MiB pages where it can.
  package static func adviseHugePages(_ buffer: UnsafeMutableRawBufferPointer) {
    #if os(Linux)
      guard let base = buffer.baseAddress, buffer.count >= 1 << 21 else {
        return
      }
      let page = 4096
      let start = (Int(bitPattern: base) + page - 1) & ~(page - 1)
      let end = (Int(bitPattern: base) + buffer.count) & ~(page - 1)
      guard end > start,
        let pointer = UnsafeMutableRawPointer(bitPattern: start)
      else { return }
      _ = madvise(pointer, end - start, MADV_HUGEPAGE)
    #endif
  }
}

extension Array {
  /// `reserveCapacity`, with the storage advised onto 2 MiB pages.
  package mutating func reserveCapacityOnHugePages(_ capacity: Int) {
    guard capacity > self.capacity else { return }
    var storage = [Element](unsafeUninitializedCapacity: capacity) {
      buffer, count in
      Memory.adviseHugePages(UnsafeMutableRawBufferPointer(buffer))
      count = 0
    }
    storage.append(contentsOf: self)
    self = storage
  }
}

extension Platform {
  /// Keeps the memory `free` returns for the process's next allocations
  /// instead of handing it back to the kernel; the executable calls it
  /// first thing.
  ///
  /// glibc trims a heap as soon as 128 KiB at its top is free, and a
  /// tile's scratch buffers (`withUnsafeTemporaryAllocation`, a few
  /// hundred KiB, on the heap) were given back after every tile and
  /// faulted in again page by page for the next: 47,000 of the 53,000 page
  /// faults of a 10³-triangle mesh's depth at 1920×1080, its first render
  /// 137 ms instead of 38 (docs/PERFORMANCE.md, its
  /// memory). This sets glibc's trim threshold
  /// (`mallopt(M_TRIM_THRESHOLD)`, looked up at run time: `<malloc.h>` is
  /// not part of the Glibc module) to its largest, and its mmap threshold
  /// to 4 MiB: setting the first freezes the second at 128 KiB, where
  /// glibc would have raised it, and a supersampled tile's scratch (over
  /// 128 KiB) was then mapped afresh for every tile (113,000 faults, 10⁴
  /// spheres at 16 samples 12 % slower). Arrays from 4 MiB up are still
  /// mapped and given back when freed.
  /// macOS's allocator keeps such regions by itself: nothing to do there.
  package static func keepFreedMemory() {
    #if canImport(Glibc)
      typealias Mallopt = @convention(c) (Int32, Int32) -> Int32
      guard let symbol = dlsym(nil, "mallopt") else { return }
      let mallopt = unsafeBitCast(symbol, to: Mallopt.self)
      let trimThreshold: Int32 = -1  // M_TRIM_THRESHOLD in <malloc.h>
      let mmapThreshold: Int32 = -3  // M_MMAP_THRESHOLD
      _ = mallopt(trimThreshold, Int32.max)
      _ = mallopt(mmapThreshold, 4 << 20)
    #endif
  }
}

extension Memory {
  /// What the process may use, the smallest limit first: its address-space
  /// and data-segment limits (`ulimit -v`, `ulimit -d`), its container's
  /// memory limit (cgroup v2 `memory.max`, or v1 `memory.limit_in_bytes`,
  /// on Linux), and the machine's memory. Each with the words that name it.
  package static func limits() -> [(bytes: Int, what: String)] {
    var result: [(bytes: Int, what: String)] = []
    func resource(_ kind: Int32, _ what: String) {
      var limit = rlimit()
      guard getrlimit(kind, &limit) == 0,
        limit.rlim_cur < UInt64(Int.max)
      else { return }
      result.append((Int(limit.rlim_cur), what))
    }
    #if canImport(Glibc)
      resource(Int32(RLIMIT_AS.rawValue), "its address-space limit (ulimit -v)")
      resource(
        Int32(RLIMIT_DATA.rawValue), "its data-segment limit (ulimit -d)")
    #else
      resource(RLIMIT_AS, "its address-space limit (ulimit -v)")
      resource(RLIMIT_DATA, "its data-segment limit (ulimit -d)")
    #endif
    #if os(Linux)
      for file in [
        "/sys/fs/cgroup/memory.max",
        "/sys/fs/cgroup/memory/memory.limit_in_bytes",
      ] {
        if let bytes = number(inFile: file), bytes < 1 << 60 {
          result.append((bytes, "its container's memory limit"))
          break
        }
      }
    #endif
    let pages = sysconf(Int32(_SC_PHYS_PAGES))
    let size = sysconf(Int32(_SC_PAGESIZE))
    if pages > 0, size > 0 {
      result.append((pages * size, "the machine's memory"))
    }
    return result.sorted { $0.bytes < $1.bytes }
  }

  /// This process's own peak resident memory in bytes, or nil where the
  /// system does not say. On Linux not `ru_maxrss`: the kernel carries the
  /// larger of a process's and its parent's peak across `exec`, so every
  /// child of a large process (one that has written a big scene)
  /// reports at least the parent's peak; `VmHWM` of /proc/self/status is
  /// this process's alone. On macOS `ru_maxrss` is the task's own, in
  /// bytes.
  package static func ownPeakBytes() -> Int? {
    #if canImport(Darwin)
      var usage = rusage()
      guard getrusage(RUSAGE_SELF, &usage) == 0 else { return nil }
      return Int(usage.ru_maxrss)
    #else
      let descriptor = open("/proc/self/status", O_RDONLY | O_CLOEXEC)
      guard descriptor >= 0 else { return nil }
      defer { close(descriptor) }
      var bytes: [UInt8] = []
      var buffer = [UInt8](repeating: 0, count: 4096)
      while true {
        let count = buffer.withUnsafeMutableBytes {
          read(descriptor, $0.baseAddress, $0.count)
        }
        guard count > 0 else { break }
        bytes += buffer[..<count]
      }
      // "VmHWM:\t  123456 kB"
      for line in String(decoding: bytes, as: UTF8.self).split(separator: "\n")
      where line.hasPrefix("VmHWM:") {
        let fields = line.split(whereSeparator: \.isWhitespace)
        guard fields.count == 3, fields[2] == "kB", let kib = Int(fields[1])
        else { return nil }
        return kib * 1024
      }
      return nil
    #endif
  }

  /// The whole number a small file holds ("max" and anything else: nil).
  static func number(inFile path: String) -> Int? {
    let descriptor = open(path, O_RDONLY | O_CLOEXEC)
    guard descriptor >= 0 else { return nil }
    defer { close(descriptor) }
    var buffer = [UInt8](repeating: 0, count: 64)
    let count = buffer.withUnsafeMutableBytes {
      read(descriptor, $0.baseAddress, 64)
    }
    guard count > 0 else { return nil }
    let text = String(decoding: buffer[..<count], as: UTF8.self)
    return Int(text.filter { !$0.isWhitespace })
  }
}
