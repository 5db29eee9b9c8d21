import Dispatch

/// Work split over threads by index range, for the reading, compiling and
/// rendering steps whose parts write disjoint memory.
package enum Parallel {
  /// Calls `body` for `parts` consecutive ranges covering 0..<count, each
  /// on its own thread when there are several.
  package static func inParts(
    _ count: Int, _ parts: Int, _ body: (Int, Range<Int>) -> Void
  ) {
    guard parts > 1 else {
      body(0, 0..<count)
      return
    }
    withoutActuallyEscaping(body) { body in
      let shared = Shared(body)
      DispatchQueue.concurrentPerform(iterations: parts) { part in
        shared.value(part, count * part / parts..<count * (part + 1) / parts)
      }
    }
  }
}

extension Parallel {
  /// How many parts to split `count` items into for `threads` threads: one
  /// per thread, each of at least `minimum` items, and one below `from`
  /// items (small inputs stay on one thread, which no wake-up of another
  /// repays).
  package static func parts(
    _ count: Int, threads: Int, from: Int, minimum: Int
  ) -> Int {
    guard count >= from, threads > 1 else { return 1 }
    return Swift.max(1, Swift.min(threads, count / Swift.max(1, minimum)))
  }
}

/// Pointers and closures shared by worker threads, which work on disjoint
/// parts of what they point to.
package struct Shared<Value>: @unchecked Sendable {
  package let value: Value
  package init(_ value: Value) { self.value = value }
}
