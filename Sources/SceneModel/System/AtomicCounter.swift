/// An integer shared between threads, behind a mutex: what the render's
/// row batches and the progress bar share. `Synchronization.Atomic` would
/// need macOS 15; a lock taken once per batch of rows costs nothing next
/// to rendering them.
public final class AtomicCounter: @unchecked Sendable {
  private let mutex: UnsafeMutablePointer<pthread_mutex_t>
  private var value: Int

  public init(_ value: Int) {
    self.value = value
    mutex = .allocate(capacity: 1)
    mutex.initialize(to: pthread_mutex_t())
    pthread_mutex_init(mutex, nil)
  }

  deinit {
    pthread_mutex_destroy(mutex)
    mutex.deinitialize(count: 1)
    mutex.deallocate()
  }

  /// The value.
  public func load() -> Int {
    pthread_mutex_lock(mutex)
    defer { pthread_mutex_unlock(mutex) }
    return value
  }

  /// Adds `amount`; returns the values before and after.
  @discardableResult
  public func add(_ amount: Int) -> (old: Int, new: Int) {
    pthread_mutex_lock(mutex)
    defer { pthread_mutex_unlock(mutex) }
    let old = value
    value &+= amount
    return (old, value)
  }

  /// Sets the value to `desired` if it is `expected`; whether it did.
  public func exchange(expected: Int, desired: Int) -> Bool {
    pthread_mutex_lock(mutex)
    defer { pthread_mutex_unlock(mutex) }
    guard value == expected else { return false }
    value = desired
    return true
  }

  /// Sets the value.
  public func store(_ newValue: Int) {
    pthread_mutex_lock(mutex)
    defer { pthread_mutex_unlock(mutex) }
    value = newValue
  }
}
