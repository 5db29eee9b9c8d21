import Geometry
import SceneDescription
import PlatformSupport

/// A bounding volume hierarchy over a scene's spheres, for camera rays: the
/// nearest sphere hit without testing every sphere.
///
/// Nodes sit in one flat array, node 0 the root, the two children of an
/// interior node adjacent and allocated in depth-first order; a leaf holds
/// up to `maximumLeafSize` consecutive spheres of `order`, the permutation
/// the records must be stored in (`CompiledScene` stores them so).
///
/// Traversal gives exactly the brute-force answer: the same t, bit for bit,
/// and the same sphere, for rays from the origin the hierarchy was built
/// for. That rests on three things:
/// - Each sphere's box holds every point its kernel can report as a hit,
///   rounding included (see `reach(radius:distance:model:)`), not just the
///   exact sphere: the textbook kernel's cancellation reports hits up to
///   about √ε·|o − centre| outside a small far sphere, and those count too.
/// - The ray–box test never rejects a box the ray meets: slabs are ordered
///   by the direction's sign rather than by min/max, so the NaN of 0·∞ (a
///   ray in a face's plane, parallel to it) drops out as "inside", and the
///   exit distance is enlarged by 1 + 2γ₃ for the three roundings of
///   (plane − origin)·(1/d) (Ize, "Robust BVH ray traversal", JCGT 2013).
/// - Ties resolve as the brute-force loop resolves them: of spheres at
///   exactly the same t, the one first in the scene's order wins. Boxes
///   entered at exactly the current best t are still opened, and a leaf
///   sphere is asked for roots up to t.nextUp, so an equal root is seen and
///   kept only when its original index is lower.
/// The one exception is a ray tangent to a sphere, whose two rounded roots
/// can come out in the wrong order: the kernel then answers differently
/// for different tMax, and which root the brute-force loop sees depends on
/// the spheres tested before it, so no other test order can promise its
/// answer.
///
/// A ray visits the nearer child first (by the sign of its direction on the
/// split axis the node records), keeps the farther one's entry distance on
/// a fixed 64-entry stack in its own frame (no allocation; the depth is
/// bounded below 64, see `forcedMedianDepth`), and skips any box entered
/// beyond the nearest hit so far.
///
/// It pays from `defaultThreshold` spheres; the measurement is there.
///
/// - Complexity: building is O(n log n): binned SAH (`binCount` bins over
///   the centroids' bounds on their widest axis) costs O(n) a level over
///   O(log n) levels. Input that SAH splits badly reaches
///   `forcedMedianDepth`, past which object medians (found by sorting)
///   take over: O(n log² n) at worst. From 2¹⁶ primitives the root's two
///   subtrees are built on two threads (measurements in
///   docs/PERFORMANCE.md). A ray visits
///   O(log n) nodes when the spheres do not overlap much, and all of them
///   in the worst case (every sphere along the ray).
package struct BoundingVolumeHierarchy<Scalar: RayScalar>: Sendable {
  /// The sphere count from which a render builds the hierarchy: below it,
  /// testing every sphere is about as fast or faster.
  ///
  /// Measured where the hierarchy breaks even against the flat loop:
  /// docs/PERFORMANCE.md, "Thresholds".
  package static var defaultThreshold: Int { 12 }

  /// One node: 32 bytes in Float, 56 in Double.
  struct Node: Equatable, Sendable {
    var lower: Vector3<Scalar>
    var upper: Vector3<Scalar>
    /// A leaf's first sphere in `order`; an interior node's first child,
    /// the second being `index + 1`.
    var index: Int32
    /// A leaf's sphere count (≥ 1), or for an interior node ~axis (−1, −2
    /// or −3), the axis its children were split along.
    var count: Int32

    var isLeaf: Bool { count > 0 }
    var axis: Int { Int(~count) }
  }

  /// Node 0 is the root; empty when there are no spheres.
  let nodes: [Node]
  /// The original index of the sphere at each leaf position.
  let order: [Int32]
  /// The deepest leaf's depth, the root's being 0.
  let depth: Int

  /// Spheres per leaf at most; SAH may stop earlier.
  static var maximumLeafSize: Int { 4 }
  /// Bins per axis for SAH.
  static var binCount: Int { 16 }
  /// From this depth on every split is an object median: the count halves
  /// each level, so no leaf is deeper than this plus log₂(2³¹ / 4) = 29,
  /// which keeps the traversal stack (one entry per level) within 64.
  static var forcedMedianDepth: Int { 32 }
  static var stackCapacity: Int { 64 }
  /// SAH cost of visiting a node (two box tests) relative to testing one
  /// sphere. Renders of 10²–10⁶ spheres were fastest from 2 to 4, about 12%
  /// faster than at 1; at 3 leaves average about three spheres.
  static var traversalCost: Double { 3 }

  /// How much a kernel's rounding widens the region it reports hits in.
  enum ErrorModel: Sendable {
    /// The cancellation-free solution (`StableKernel`): a hit lies within
    /// r + O(ε)·(r + |o − centre|) of the centre.
    case cancellationFree
    /// The textbook formula (`NaiveKernel`, and any kernel not known to be
    /// better): b² − 4ac cancels, so a hit lies within
    /// √(r² + O(ε)·|o − centre|²) of the centre.
    case textbook
  }
}

extension BoundingVolumeHierarchy {
  /// The hierarchy over `spheres` as the kernel stores them, for rays from
  /// `rayOrigin` in the kernel's frame (`Kernel.frameOrigin(eye:)`).
  ///
  /// - Parameters concurrentFrom, threads: see
  ///   `init(boxes:concurrentFrom:threads:)`.
  init<Kernel: IntersectionKernel>(
    spheres: [Kernel.SphereRecord], kernel: Kernel.Type,
    rayOrigin: Vector3<Scalar>, concurrentFrom: Int = 1 << 16,
    threads: Int = 2
  ) where Kernel.Scalar == Scalar {
    // A protocol requirement would be the natural home for this, but the
    // model is a property of the two kernels this module defines; anything
    // else gets the textbook bound, which is looser.
    let model: ErrorModel =
      Kernel.self == StableKernel<Scalar>.self ? .cancellationFree : .textbook
    var (primitives, summary) = spheres.withUnsafeBufferPointer { records in
      Self.primitives(
        count: records.count, concurrentFrom: concurrentFrom, threads: threads
      ) {
        let (center, radius) = Kernel.centerAndRadius(records[$0])
        return Self.box(
          center: center, radius: radius, rayOrigin: rayOrigin, model: model)
      }
    }
    self.init(
      &primitives, summary, concurrentFrom: concurrentFrom, threads: threads)
  }

  /// A box holding every point at which a kernel of `model` can report a
  /// hit on the sphere for a ray from `rayOrigin`, rounded outward.
  static func box(
    center: Vector3<Scalar>, radius: Scalar, rayOrigin: Vector3<Scalar>,
    model: ErrorModel
  ) -> (lower: Vector3<Scalar>, upper: Vector3<Scalar>) {
    // |c − o|, scaled by its largest component so that the squares cannot
    // overflow or underflow; 1 + γ₄ covers its own roundings.
    let offset = center - rayOrigin
    let largest = offset.maxMagnitude
    let distance =
      largest > 0 && largest.isFinite
      ? largest * (offset / largest).length * (1 + gamma(4)) : largest
    let r = reach(radius: radius.magnitude, distance: distance, model: model)
    let lower = Vector3(
      (center.x - r).nextDown, (center.y - r).nextDown,
      (center.z - r).nextDown)
    let upper = Vector3(
      (center.x + r).nextUp, (center.y + r).nextUp, (center.z + r).nextUp)
    // A NaN centre or radius never hits in the kernel; an infinite box
    // keeps NaN out of the unions and the bins all the same.
    if !(lower.x <= upper.x && lower.y <= upper.y && lower.z <= upper.z) {
      let infinity = Scalar.infinity
      return (
        Vector3(-infinity, -infinity, -infinity),
        Vector3(infinity, infinity, infinity)
      )
    }
    return (lower, upper)
  }

  /// The distance from the centre within which a kernel of `model` can
  /// report a hit, for a sphere of radius `radius` at distance at most
  /// `distance` from the rays' origin.
  ///
  /// Both are first-order error bounds with their constants at least
  /// doubled. Cancellation-free: the closest-approach vector l is computed
  /// to γ₁₀·|p| per component, so a reported hit has |l| ≤ r(1 + γ₃) +
  /// γ₁₈·|p|, and its t carries a few more relative roundings: γ₃₂·(D + r)
  /// covers both. Textbook: b̂² − 4âĉ is within γ₆₈·|d|²·(D² + r²) of
  /// 4a(r² − ℓ²) (ℓ the centre's distance from the line), so a hit has
  /// ℓ² ≤ r² + γ₁₇·(D² + r²); the reported point, √Δ̂/2a along the ray
  /// from the closest approach, lies within √(r² + γ₃₄·(D² + r²)) of the
  /// centre. γ₆₄ is used, plus γ₁₆·(D + r) for the roundings of t. For a
  /// Float sphere 1000 away that reach is about 2 whatever its radius.
  static func reach(
    radius r: Scalar, distance: Scalar, model: ErrorModel
  ) -> Scalar {
    switch model {
    case .cancellationFree:
      return r * (1 + gamma(8)) + gamma(32) * (distance + r)
    case .textbook:
      // √(r²(1 + γ) + γ·D²), scaled so that neither square overflows or
      // underflows.
      let a = r * (1 + gamma(64))
      let b = gamma(64).squareRoot() * distance
      let scale = Swift.max(a, b)
      guard scale > 0 && scale.isFinite else {
        return scale + gamma(16) * (distance + r)
      }
      let (x, y) = (a / scale, b / scale)
      return scale * (x * x + y * y).squareRoot() * (1 + gamma(4))
        + gamma(16) * (distance + r)
    }
  }

  /// γₙ = nu / (1 − nu), u the unit roundoff: the bound on n roundings.
  static func gamma(_ n: Int) -> Scalar {
    let nu = Scalar(n) * Scalar.ulpOfOne / 2
    return nu / (1 - nu)
  }

  /// Builds over boxes given in the original order.
  ///
  /// - Parameters:
  ///   - concurrentFrom: from this many boxes the work is shared by up to
  ///     `threads` threads: the primitives and their bounds and the root's
  ///     bins in one part per thread, each of at least half this many
  ///     boxes, then the root's two subtrees on two threads. The result is
  ///     the same for any count: the parts' bounds and bins are merged in
  ///     order (a minimum keeps the first of equal values and a maximum
  ///     the last, as one pass would), each subtree is built as the
  ///     sequential build would build it, and the subtrees are spliced
  ///     into the same depth-first layout.
  ///   - threads: the render's; 1 builds on the calling thread alone.
  init(
    boxes: [(lower: Vector3<Scalar>, upper: Vector3<Scalar>)],
    concurrentFrom: Int = 1 << 16, threads: Int = 2
  ) {
    self = boxes.withUnsafeBufferPointer { boxes in
      Self(
        count: boxes.count, concurrentFrom: concurrentFrom, threads: threads
      ) { boxes[$0] }
    }
  }

  /// Builds over `count` boxes given by `box` in the original order, as
  /// `init(boxes:concurrentFrom:threads:)` does, without an array of them:
  /// `box` is called once per index, from up to `threads` threads from
  /// `concurrentFrom` boxes on, so it must be safe to call concurrently.
  init(
    count: Int, concurrentFrom: Int = 1 << 16, threads: Int = 2,
    box: (Int) -> (lower: Vector3<Scalar>, upper: Vector3<Scalar>)
  ) {
    var (primitives, summary) = Self.primitives(
      count: count, concurrentFrom: concurrentFrom, threads: threads, box: box)
    self.init(
      &primitives, summary, concurrentFrom: concurrentFrom, threads: threads)
  }

  /// Partitions `primitives` in place: an array passed by value was
  /// copied, 80 MB for 10⁶ spheres.
  private init(
    _ primitives: inout [Primitive], _ summary: Summary, concurrentFrom: Int,
    threads: Int
  ) {
    var builder = Builder()
    primitives.withUnsafeMutableBufferPointer { primitives in
      builder.build(
        primitives, summary: summary,
        parts: Self.parts(
          primitives.count, concurrentFrom: concurrentFrom, threads: threads))
    }
    nodes = builder.nodes
    order = primitives.map(\.index)
    depth = builder.depth
    precondition(
      depth < Self.stackCapacity, "BVH deeper than the traversal stack")
  }

  /// The primitive of each box, in the original order, and their bounds,
  /// in one pass: a separate array of boxes and a pass for the root's
  /// bounds cost a tenth of the build of 10⁶ spheres.
  static func primitives(
    count: Int, concurrentFrom: Int, threads: Int,
    box: (Int) -> (lower: Vector3<Scalar>, upper: Vector3<Scalar>)
  ) -> (primitives: [Primitive], summary: Summary) {
    let parts = Self.parts(
      count, concurrentFrom: concurrentFrom, threads: threads)
    var summaries = [Summary](repeating: Summary(), count: parts)
    let primitives = [Primitive](unsafeUninitializedCapacity: count) {
      buffer, initialized in
      summaries.withUnsafeMutableBufferPointer { summaries in
        let shared = Shared((buffer, summaries))
        Parallel.inParts(count, parts) { part, range in
          let (buffer, summaries) = shared.value
          var summary = Summary()
          for index in range {
            let (lower, upper) = box(index)
            let primitive = Primitive(
              lower: lower, upper: upper,
              index: Int32(truncatingIfNeeded: index))
            (buffer.baseAddress.unsafelyUnwrapped + index).initialize(
              to: primitive)
            summary.include(primitive)
          }
          summaries[part] = summary
        }
      }
      initialized = count
    }
    var summary = Summary()
    for part in summaries { summary.include(part) }
    return (primitives, summary)
  }

  /// The parts a build of `count` primitives shares out: one per thread,
  /// each of at least half `concurrentFrom`, and one below it.
  static func parts(_ count: Int, concurrentFrom: Int, threads: Int) -> Int {
    Parallel.parts(
      count, threads: threads, from: concurrentFrom,
      minimum: concurrentFrom / 2)
  }
}
