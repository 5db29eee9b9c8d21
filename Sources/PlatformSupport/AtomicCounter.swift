/// An integer shared between threads, behind a mutex (`Locked`): what the
/// render's row batches and the progress bar share.
/// `Synchronization.Atomic` would need macOS 15; a lock taken once per
/// batch of rows costs nothing next to rendering them.
package final class AtomicCounter: @unchecked Sendable {
  private let value: Locked<Int>

  package init(_ value: Int) {
    self.value = Locked(value)
  }

  /// The value.
  package func load() -> Int {
    value.withLock { $0 }
  }

  /// Adds `amount`; returns the values before and after.
  @discardableResult
  package func add(_ amount: Int) -> (old: Int, new: Int) {
    value.withLock { value in
      let old = value
      value &+= amount
      return (old, value)
    }
  }

  /// Sets the value to `desired` if it is `expected`; whether it did.
  package func exchange(expected: Int, desired: Int) -> Bool {
    value.withLock { value in
      guard value == expected else { return false }
      value = desired
      return true
    }
  }

  /// Sets the value.
  package func store(_ newValue: Int) {
    value.withLock { $0 = newValue }
  }
}
