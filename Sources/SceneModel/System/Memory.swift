/// Large arrays on 2 MiB pages: a 4 KiB page fault for every 4 KiB of the
/// arrays of a million spheres, or of a render's buffers, was a tenth to a
/// quarter of the step that first wrote them.
public enum Memory {
  /// Asks the kernel to back `buffer` with 2 MiB pages where it can.
  public static func adviseHugePages(_ buffer: UnsafeMutableRawBufferPointer) {
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
  public mutating func reserveCapacityOnHugePages(_ capacity: Int) {
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
  /// 137 ms instead of 38 (docs/PERFORMANCE.md, "Edge planes, corner
  /// projection and page faults"). This sets glibc's trim threshold
  /// (`mallopt(M_TRIM_THRESHOLD)`, looked up at run time: `<malloc.h>` is
  /// not part of the Glibc module) to its largest, and its mmap threshold
  /// to 4 MiB: setting the first freezes the second at 128 KiB, where
  /// glibc would have raised it, and a supersampled tile's scratch (over
  /// 128 KiB) was then mapped afresh for every tile (113,000 faults, 10⁴
  /// spheres at 16 samples 12 % slower). Arrays from 4 MiB up are still
  /// mapped and given back when freed.
  /// macOS's allocator keeps such regions by itself: nothing to do there.
  public static func keepFreedMemory() {
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
