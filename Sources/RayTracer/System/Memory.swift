/// Large arrays on 2 MiB pages: a 4 KiB page fault for every 4 KiB of the
/// arrays of a million spheres, or of a render's buffers, was a tenth to a
/// quarter of the step that first wrote them.
enum Memory {
  /// Asks the kernel to back `buffer` with 2 MiB pages where it can.
  static func adviseHugePages(_ buffer: UnsafeMutableRawBufferPointer) {
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
  mutating func reserveCapacityOnHugePages(_ capacity: Int) {
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
