import Geometry
import SceneDescription
import PlatformSupport

/// What a signal handler must undo for the outputs in flight, in fixed C
/// storage that it can read without allocating or locking: temporary files
/// to remove, and targets already replaced in a batch that has not finished
/// (each to be put back from its backup, or removed if it is new).
///
/// Every entry is written last byte first and cleared by its first byte,
/// so a handler never sees half an entry.
enum PendingFiles {
  /// What the handler does with an entry.
  enum Action: CChar {
    /// Unlink the path.
    case remove = 0x54
    /// Rename the first path (a backup) over the second (its target).
    case restore = 0x52
  }

  static let slots = 32
  static let slotSize = 2 * 4096 + 2
  nonisolated(unsafe) static let storage: UnsafeMutablePointer<CChar> = {
    let pointer = UnsafeMutablePointer<CChar>.allocate(
      capacity: slots * slotSize)
    pointer.initialize(repeating: 0, count: slots * slotSize)
    return pointer
  }()
  nonisolated(unsafe) static var installed = false

  /// Records an entry; false when every slot is taken or the paths are too
  /// long to store.
  static func add(_ action: Action, _ path: String, _ second: String = "")
    -> Bool
  {
    let bytes =
      [action.rawValue] + Array(path.utf8CString) + Array(second.utf8CString)
    guard bytes.count <= slotSize, !path.isEmpty else { return false }
    for slot in 0..<slots where storage[slot * slotSize] == 0 {
      for (index, byte) in bytes.enumerated().reversed() {
        storage[slot * slotSize + index] = byte
      }
      return true
    }
    return false
  }

  /// Forgets the entry for `path` (its first path).
  static func remove(_ path: String) {
    for slot in 0..<slots where storage[slot * slotSize] != 0 {
      if String(cString: storage + slot * slotSize + 1) == path {
        storage[slot * slotSize] = 0
      }
    }
  }

  /// Undoes every entry: what the handlers run. Only async-signal-safe
  /// calls (rename, unlink).
  static func undoAll() {
    for slot in 0..<slots {
      let entry = storage + slot * slotSize
      let first = entry + 1
      switch entry.pointee {
      case Action.remove.rawValue:
        unlink(first)
      case Action.restore.rawValue:
        let second = first + strlen(first) + 1
        rename(first, second)
        // Where the backup and the target were still one file, rename did
        // nothing and the backup's name remains.
        unlink(first)
      default:
        continue
      }
      entry.pointee = 0
    }
  }

  /// Every catchable signal whose default action ends the process, and so
  /// must undo the outputs in flight first: hang-up, interrupt, quit
  /// (Ctrl-\, whose default would also show the runtime's crash report),
  /// terminate, a closed pipe, the alarm and profiling timers, the two
  /// user signals, and the CPU-time and file-size limits.
  static let terminating = [
    SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2,
    SIGXCPU, SIGXFSZ, SIGVTALRM, SIGPROF,
  ]

  /// Installs, once, handlers that undo the outputs in flight and then end
  /// the process as the signal would (its default action, so the parent
  /// sees the signal in the status). A signal ignored when the process
  /// started (`nohup`, a shell's `cmd &`) stays ignored: the handler would
  /// end a run its parent asked to outlive the signal.
  static func installHandlers() {
    guard !installed else { return }
    installed = true
    for signalNumber in terminating
    where !Platform.ignoreReportingWhetherIgnored(signalNumber) {
      signal(signalNumber) { received in
        PendingFiles.undoAll()
        signal(received, SIG_DFL)
        raise(received)
      }
    }
  }
}
