import Geometry
import SceneDescription

/// The nearest hit along one ray so far, and the tie rule every search of
/// the fast engine keeps.
///
/// The rule is the course loop's: objects are tested in scene order, each
/// asked only for a hit strictly before the best t (`test`), so at equal t
/// the object first in the scene stays. Searches that visit objects out of
/// order (the hierarchies) give the same answer by asking for hits up to
/// `limit`, just above the best t once there is one, and keeping an equal
/// t only from an object earlier in scene order (`offer`).
struct NearestHit<Scalar: RayScalar, What> {
  /// The best t so far; the bound given at the start until something is
  /// hit.
  private(set) var t: Scalar
  /// What the best hit is, nil until something is hit.
  private(set) var what: What?
  /// The bound to hand an out-of-order search's next test: `t`, then
  /// `t.nextUp` once something is hit, so that a tie comes back.
  private(set) var limit: Scalar
  /// The best hit's place in scene order, for out-of-order searches.
  private var order = Int32.max

  /// Nothing hit yet; hits count in (0, tMax).
  @inline(__always)
  init(before tMax: Scalar) {
    t = tMax
    limit = tMax
  }

  /// What a search of the same scene-order kind found: `what` at `t`, or
  /// nothing before `t` when `what` is nil.
  @inline(__always)
  init(_ t: Scalar, _ what: What?) {
    self.t = t
    self.what = what
    limit = t
  }

  /// Scene order: `intersect` is asked for a hit strictly before `t`, and
  /// what it finds is the new best.
  @inline(__always)
  mutating func test(
    _ what: @autoclosure () -> What, _ intersect: (Scalar) -> Scalar?
  ) {
    if let found = intersect(t) {
      t = found
      self.what = what()
      limit = found
    }
  }

  /// Out of order: keeps `found` when it is nearer, or as near and earlier
  /// in scene order (`order`); true when it was kept.
  @inline(__always)
  mutating func offer(_ found: Scalar, _ what: What, order: Int32) -> Bool {
    guard found < t || (found == t && order < self.order) else {
      return false
    }
    t = found
    self.what = what
    self.order = order
    limit = found.nextUp
    return true
  }

  /// The best hit: its t and what it is, or nil.
  var hit: (t: Scalar, what: What)? {
    what.map { (t, $0) }
  }
}
