import Dispatch

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
///   take over: O(n log² n) at worst. 10⁶ random spheres take about 0.5 s
///   of CPU in a release build on the project's 2-core machine; from 2¹⁶
///   spheres the root's two subtrees are built on two threads, which cut
///   the wall time 1.8× when the second core was idle. A ray visits
///   O(log n) nodes when the spheres do not overlap much, and all of them
///   in the worst case (every sphere along the ray).
public struct BoundingVolumeHierarchy<Scalar: RayScalar>: Sendable {
  /// The sphere count from which a render builds the hierarchy: below it,
  /// testing every sphere is about as fast or faster.
  ///
  /// Measured with a release build on the project's 2-core Linux machine,
  /// one render thread, by a scratch benchmark compiled into a copy of this
  /// module: 384×384 depth-only camera rays through random scenes of n
  /// spheres (radii 0.2–1 or 1–4 in a 20-unit cube, or 0.1–0.5 in a
  /// 40-unit cube, 30 units from the eye; three seeds each), the flat loop
  /// against the hierarchy, thread CPU time, best of five. The hierarchy
  /// broke even at 6–10 spheres with the stable kernel in Float and below
  /// 4 in Double (whose flat loop costs about 4× Float's per sphere), and
  /// at 16–32 with the textbook kernel, whose flat loop is the cheapest.
  /// At 12 the stable kernel gains 1.1–1.5× (Float) and 2.5–3.3× (Double),
  /// and the textbook kernel loses at most 20% short of its break-even.
  public static var defaultThreshold: Int { 12 }

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

// MARK: - Building

extension BoundingVolumeHierarchy {
  /// The hierarchy over `spheres` as the kernel stores them, for rays from
  /// `rayOrigin` in the kernel's frame (`Kernel.frameOrigin(eye:)`).
  ///
  /// - Parameter concurrentFrom: see `init(boxes:concurrentFrom:)`.
  init<Kernel: IntersectionKernel>(
    spheres: [Kernel.SphereRecord], kernel: Kernel.Type,
    rayOrigin: Vector3<Scalar>, concurrentFrom: Int = 1 << 16
  ) where Kernel.Scalar == Scalar {
    // A protocol requirement would be the natural home for this, but the
    // model is a property of the two kernels this module defines; anything
    // else gets the textbook bound, which is looser.
    let model: ErrorModel =
      Kernel.self == StableKernel<Scalar>.self ? .cancellationFree : .textbook
    var (primitives, summary) = spheres.withUnsafeBufferPointer { records in
      Self.primitives(count: records.count, concurrentFrom: concurrentFrom) {
        let (center, radius) = Kernel.centerAndRadius(records[$0])
        return Self.box(
          center: center, radius: radius, rayOrigin: rayOrigin, model: model)
      }
    }
    self.init(&primitives, summary, concurrentFrom: concurrentFrom)
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
  /// - Parameter concurrentFrom: from this many boxes the work is shared
  ///   by two threads: the primitives and their bounds, the root's bins,
  ///   then the root's two subtrees. The result is the same either way:
  ///   the bounds of the two halves are merged in order (a minimum keeps
  ///   the first of equal values and a maximum the last, as one pass
  ///   would), each subtree is built as the sequential build would build
  ///   it, and the subtrees are spliced into the same depth-first layout.
  init(
    boxes: [(lower: Vector3<Scalar>, upper: Vector3<Scalar>)],
    concurrentFrom: Int = 1 << 16
  ) {
    var (primitives, summary) = boxes.withUnsafeBufferPointer { boxes in
      Self.primitives(count: boxes.count, concurrentFrom: concurrentFrom) {
        boxes[$0]
      }
    }
    self.init(&primitives, summary, concurrentFrom: concurrentFrom)
  }

  /// Partitions `primitives` in place: an array passed by value was
  /// copied, 80 MB for 10⁶ spheres.
  private init(
    _ primitives: inout [Primitive], _ summary: Summary, concurrentFrom: Int
  ) {
    var builder = Builder()
    primitives.withUnsafeMutableBufferPointer { primitives in
      builder.build(
        primitives, summary: summary, concurrentFrom: concurrentFrom)
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
    count: Int, concurrentFrom: Int,
    box: (Int) -> (lower: Vector3<Scalar>, upper: Vector3<Scalar>)
  ) -> (primitives: [Primitive], summary: Summary) {
    let parts = count >= concurrentFrom ? 2 : 1
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


  /// A sphere's box while building, carried through the partitions so that
  /// each pass reads memory in order.
  struct Primitive {
    var lower: Vector3<Scalar>
    var upper: Vector3<Scalar>
    var centroid: Vector3<Scalar>
    var index: Int32

    init(lower: Vector3<Scalar>, upper: Vector3<Scalar>, index: Int32) {
      self.lower = lower
      self.upper = upper
      self.index = index
      // Halves first so that huge boxes do not overflow; an unbounded box
      // (a NaN or overflowing sphere) has no centre and sits at 0.
      let middle = lower * 0.5 + upper * 0.5
      centroid = Vector3(
        middle.x.isNaN ? 0 : middle.x, middle.y.isNaN ? 0 : middle.y,
        middle.z.isNaN ? 0 : middle.z)
    }
  }

  /// An axis-aligned box that starts empty (lower +∞, upper −∞).
  struct Bounds {
    var lower = Vector3<Scalar>(.infinity, .infinity, .infinity)
    var upper = Vector3<Scalar>(-.infinity, -.infinity, -.infinity)

    @inline(__always)
    mutating func include(lower l: Vector3<Scalar>, upper u: Vector3<Scalar>) {
      lower = Vector3(
        Swift.min(lower.x, l.x), Swift.min(lower.y, l.y),
        Swift.min(lower.z, l.z))
      upper = Vector3(
        Swift.max(upper.x, u.x), Swift.max(upper.y, u.y),
        Swift.max(upper.z, u.z))
    }

    /// Half the surface area, in Double so that Float boxes of 10²⁰ do not
    /// overflow it; ∞ for an unbounded box.
    var halfArea: Double {
      let dx = Double(upper.x) - Double(lower.x)
      let dy = Double(upper.y) - Double(lower.y)
      let dz = Double(upper.z) - Double(lower.z)
      let area = dx * dy + dy * dz + dz * dx
      return area.isNaN ? .infinity : area
    }
  }

  /// The boxes' and the centroids' bounds of a range of primitives.
  struct Summary {
    var bounds = Bounds()
    var centroids = Bounds()

    @inline(__always)
    mutating func include(_ primitive: Primitive) {
      bounds.include(lower: primitive.lower, upper: primitive.upper)
      centroids.include(lower: primitive.centroid, upper: primitive.centroid)
    }

    @inline(__always)
    mutating func include(_ other: Summary) {
      bounds.include(lower: other.bounds.lower, upper: other.bounds.upper)
      centroids.include(
        lower: other.centroids.lower, upper: other.centroids.upper)
    }

    init() {}

    init(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ range: Range<Int>
    ) {
      for primitive in primitives[range] { include(primitive) }
    }
  }

  struct Bin {
    var summary = Summary()
    var count = 0
    /// area·count of this bin and those above it together, for the sweep.
    var rightCost: Double = 0
  }

  /// How a node's centroids fall into bins: along the widest axis whose
  /// extent and its reciprocal are finite. Nodes of a few spheres use
  /// fewer bins: two per sphere, at least four.
  ///
  /// Only one axis: binning all three cost twice the build time and
  /// rendered no faster in the benchmarks behind `defaultThreshold`.
  struct Binning {
    var axis: Int
    var origin: Scalar
    var scale: Scalar
    var count: Int

    /// Nil when no axis can be binned (all centroids equal, or an extent
    /// that overflows or whose reciprocal does).
    init?(_ centroids: Bounds, primitives: Int) {
      count = Swift.min(
        BoundingVolumeHierarchy.binCount, Swift.max(4, 2 * primitives))
      axis = -1
      scale = 0
      for candidate in 0..<3 {
        let extent = centroids.upper[candidate] - centroids.lower[candidate]
        let candidateScale = Scalar(count) / extent
        guard extent > 0 && extent.isFinite && candidateScale.isFinite else {
          continue
        }
        if axis < 0 || candidateScale < scale {
          axis = candidate
          scale = candidateScale
        }
      }
      guard axis >= 0 else { return nil }
      origin = centroids.lower[axis]
    }

    @inline(__always)
    func bin(_ centroid: Vector3<Scalar>) -> Int {
      Builder.bin(centroid[axis], origin, scale, count)
    }
  }

  /// The state of one build: nodes so far and bins reused by every node.
  struct Builder {
    var nodes: [Node] = []
    var depth = 0
    /// The node's bins first, then three sets more for `fill`.
    var bins = [Bin](
      repeating: Bin(), count: 4 * BoundingVolumeHierarchy.binCount)
    /// Positions `partition` swaps, kept for the next node.
    var misplaced: [Int32] = []

    /// One node still to build: its slot, its primitives and their bounds.
    struct Task {
      var node: Int
      var range: Range<Int>
      var summary: Summary
      var depth: Int
      /// Whether `bins` holds its bins already (only ever the root's).
      var binned = false
    }

    /// Where a node's primitives go; a split has partitioned them.
    enum Decision {
      case leaf
      case split(middle: Int, axis: Int, left: Summary, right: Summary)
    }

    static var placeholder: Node {
      Node(lower: .zero, upper: .zero, index: 0, count: 0)
    }

    mutating func build(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, summary: Summary,
      concurrentFrom: Int
    ) {
      guard !primitives.isEmpty else { return }
      nodes.reserveCapacity(2 * primitives.count - 1)
      nodes.append(Self.placeholder)
      var root = Task(
        node: 0, range: primitives.indices, summary: summary, depth: 0)
      guard primitives.count >= concurrentFrom else {
        grow(primitives, from: root)
        return
      }
      // The root's bins and the root here, then each child's subtree on its
      // own thread into its own array, its root at 0.
      root.binned = binInParts(primitives, summary)
      guard let (left, right) = place(primitives, root) else { return }
      let shared = Shared(primitives)
      var halves = [Builder(), Builder()]
      halves.withUnsafeMutableBufferPointer { halves in
        let results = Shared(halves)
        DispatchQueue.concurrentPerform(iterations: 2) { half in
          var task = half == 0 ? left : right
          task.node = 0
          var builder = Builder()
          builder.nodes.reserveCapacity(2 * task.range.count - 1)
          builder.nodes.append(Self.placeholder)
          builder.grow(shared.value, from: task)
          results.value[half] = builder
        }
      }
      splice(halves[0], halves[1], at: left.node)
    }

    /// Fills `bins` for the root as `bestBinnedSplit` would, each half of
    /// the primitives on its own thread; the halves' bins are merged in
    /// order (a minimum keeps the first of equal values and a maximum the
    /// last, as one pass does), so they are the bins one pass gives.
    /// False when the root is not binned.
    mutating func binInParts(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ summary: Summary
    ) -> Bool {
      guard primitives.count > 1,
        BoundingVolumeHierarchy.forcedMedianDepth > 0,
        let binning = Binning(summary.centroids, primitives: primitives.count)
      else { return false }
      let empty = [Bin](repeating: Bin(), count: binning.count)
      var parts = [empty, empty]
      parts.withUnsafeMutableBufferPointer { parts in
        let shared = Shared((primitives, parts))
        Parallel.inParts(primitives.count, 2) { part, range in
          let (primitives, parts) = shared.value
          parts[part].withUnsafeMutableBufferPointer { bins in
            Self.fill(bins, primitives, range, binning)
          }
        }
      }
      for bin in 0..<binning.count {
        var merged = Bin()
        for part in parts {
          merged.count += part[bin].count
          merged.summary.include(part[bin].summary)
        }
        bins[bin] = merged
      }
      return true
    }

    /// Adds each primitive of the range to its bin in the first set of
    /// `binning.count` bins in `bins`.
    ///
    /// A long range is binned as four blocks at once, each into a set of
    /// its own that is then merged in order into the first: consecutive
    /// primitives in one bin otherwise each wait for the other's update of
    /// it, which made this loop a quarter of the build. Merged in order,
    /// the bins are those one pass gives: of equal values (±0) a minimum
    /// keeps the first and a maximum the last, however they are grouped.
    static func fill(
      _ bins: UnsafeMutableBufferPointer<Bin>,
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ range: Range<Int>,
      _ binning: Binning
    ) {
      let count = binning.count
      @inline(__always)
      func add(_ index: Int, to set: Int) {
        let primitive = primitives[index]
        let bin = set * count + binning.bin(primitive.centroid)
        bins[bin].count += 1
        bins[bin].summary.include(primitive)
      }
      guard range.count >= 64, bins.count >= 4 * count else {
        for index in range { add(index, to: 0) }
        return
      }
      for bin in count..<4 * count { bins[bin] = Bin() }
      let quarter = range.count / 4
      let start = range.lowerBound
      for offset in start..<start + quarter {
        add(offset, to: 0)
        add(offset + quarter, to: 1)
        add(offset + 2 * quarter, to: 2)
        add(offset + 3 * quarter, to: 3)
      }
      for index in start + 4 * quarter..<range.upperBound { add(index, to: 3) }
      for set in 1..<4 {
        for bin in 0..<count {
          bins[bin].count += bins[set * count + bin].count
          bins[bin].summary.include(bins[set * count + bin].summary)
        }
      }
    }

    /// Appends two subtrees built apart as the children at `first` and
    /// `first + 1` (the last two nodes), in the order a sequential build
    /// allocates them: the left subtree's pairs, then the right's.
    mutating func splice(_ left: Builder, _ right: Builder, at first: Int) {
      let leftOffset = nodes.count - 1
      let rightOffset = leftOffset + left.nodes.count - 1
      func moved(_ node: Node, by offset: Int) -> Node {
        var node = node
        if !node.isLeaf { node.index += Int32(truncatingIfNeeded: offset) }
        return node
      }
      nodes[first] = moved(left.nodes[0], by: leftOffset)
      nodes[first + 1] = moved(right.nodes[0], by: rightOffset)
      for node in left.nodes.dropFirst() {
        nodes.append(moved(node, by: leftOffset))
      }
      for node in right.nodes.dropFirst() {
        nodes.append(moved(node, by: rightOffset))
      }
      depth = Swift.max(depth, left.depth, right.depth)
    }

    /// Builds the subtree of `root`, whose slot exists, depth first.
    mutating func grow(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, from root: Task
    ) {
      // An explicit stack rather than recursion. The right child is pushed
      // first so that the left subtree's pairs are allocated next: that
      // makes the array depth-first.
      var tasks = [root]
      while let task = tasks.popLast() {
        guard let (left, right) = place(primitives, task) else { continue }
        tasks.append(right)
        tasks.append(left)
      }
    }

    /// Writes the task's node; for an interior node, allocates its two
    /// children and returns their tasks.
    mutating func place(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ task: Task
    ) -> (left: Task, right: Task)? {
      let range = task.range
      let bounds = task.summary.bounds
      switch decide(
        primitives, range, task.summary, depth: task.depth, binned: task.binned)
      {
      case .leaf:
        nodes[task.node] = Node(
          lower: bounds.lower, upper: bounds.upper,
          index: Int32(truncatingIfNeeded: range.lowerBound),
          count: Int32(truncatingIfNeeded: range.count))
        depth = Swift.max(depth, task.depth)
        return nil
      case .split(let middle, let axis, let left, let right):
        let child = nodes.count
        nodes.append(Self.placeholder)
        nodes.append(Self.placeholder)
        nodes[task.node] = Node(
          lower: bounds.lower, upper: bounds.upper,
          index: Int32(truncatingIfNeeded: child),
          count: ~Int32(truncatingIfNeeded: axis))
        return (
          Task(
            node: child, range: range.lowerBound..<middle, summary: left,
            depth: task.depth + 1),
          Task(
            node: child + 1, range: middle..<range.upperBound,
            summary: right, depth: task.depth + 1)
        )
      }
    }

    /// Leaf or split, and for a split, partitions the range.
    mutating func decide(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ range: Range<Int>,
      _ summary: Summary, depth: Int, binned: Bool
    ) -> Decision {
      typealias BVH = BoundingVolumeHierarchy
      let count = range.count
      let small = count <= BVH.maximumLeafSize
      if count == 1 { return .leaf }
      if depth >= BVH.forcedMedianDepth {
        return small ? .leaf : medianSplit(primitives, range, summary)
      }
      guard
        let best = bestBinnedSplit(
          primitives, range, summary.centroids, binned: binned)
      else {
        return small ? .leaf : medianSplit(primitives, range, summary)
      }
      if small {
        let nodeArea = summary.bounds.halfArea
        let splitCost =
          nodeArea > 0 && nodeArea.isFinite
          ? BVH.traversalCost + best.cost / nodeArea : Double(count)
        if Double(count) <= splitCost { return .leaf }
      }
      let middle = partition(
        primitives, range, axis: best.axis, origin: best.origin,
        scale: best.scale, bins: best.bins, firstRight: best.bin)
      return .split(
        middle: middle, axis: best.axis, left: best.left, right: best.right)
    }

    /// The SAH-cheapest bin boundary (least Σ area·count of the two sides)
    /// on the axis `Binning` chooses, or nil when there is none. Bins the
    /// range unless `binned` says `bins` holds its bins already.
    mutating func bestBinnedSplit(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ range: Range<Int>,
      _ centroids: Bounds, binned: Bool
    ) -> (
      axis: Int, origin: Scalar, scale: Scalar, bins: Int, bin: Int,
      cost: Double, left: Summary, right: Summary
    )? {
      guard let binning = Binning(centroids, primitives: range.count) else {
        return nil
      }
      let (axis, origin, scale, binCount) = (
        binning.axis, binning.origin, binning.scale, binning.count
      )
      return bins.withUnsafeMutableBufferPointer { bins in
        if !binned {
          for index in 0..<binCount { bins[index] = Bin() }
          Self.fill(bins, primitives, range, binning)
        }
        var right = Bounds()
        var rightCount = 0
        for bin in stride(from: binCount - 1, to: 0, by: -1) {
          right.include(
            lower: bins[bin].summary.bounds.lower,
            upper: bins[bin].summary.bounds.upper)
          rightCount += bins[bin].count
          bins[bin].rightCost =
            rightCount == 0 ? 0 : right.halfArea * Double(rightCount)
        }
        var best: (bin: Int, cost: Double)?
        var left = Bounds()
        var leftCount = 0
        for bin in 1..<binCount {
          left.include(
            lower: bins[bin - 1].summary.bounds.lower,
            upper: bins[bin - 1].summary.bounds.upper)
          leftCount += bins[bin - 1].count
          guard leftCount > 0 && leftCount < range.count else { continue }
          let cost = left.halfArea * Double(leftCount) + bins[bin].rightCost
          // Strict: the first of equal costs wins, so that the tree depends
          // on nothing but the input.
          if cost < (best?.cost ?? .infinity) { best = (bin, cost) }
        }
        guard let best else { return nil }
        // The sides' bounds are the unions of their bins', so neither child
        // needs a pass of its own for them.
        var sides = (left: Summary(), right: Summary())
        for bin in 0..<binCount {
          if bin < best.bin {
            sides.left.include(bins[bin].summary)
          } else {
            sides.right.include(bins[bin].summary)
          }
        }
        return (
          axis, origin, scale, binCount, best.bin, best.cost, sides.left,
          sides.right
        )
      }
    }

    /// The bin of a centroid coordinate: 0 for the least, binCount − 1 for
    /// the greatest (their product with the scale rounds to binCount).
    @inline(__always)
    static func bin(
      _ value: Scalar, _ origin: Scalar, _ scale: Scalar, _ count: Int
    ) -> Int {
      // Through Double: Int(Double) is one instruction, where the generic
      // Int(Scalar) takes the slow path even when specialised.
      let position = Double((value - origin) * scale)
      let last = count - 1
      return position < Double(last) ? (position > 0 ? Int(position) : 0) : last
    }

    /// Splits the range in half by centroid along `axis`, original index
    /// breaking ties, so the halves are the same on every build. When all
    /// centroids coincide any halving is as good, and sorting is skipped.
    func medianSplit(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ range: Range<Int>,
      _ summary: Summary
    ) -> Decision {
      let extent = summary.centroids.upper - summary.centroids.lower
      let axis =
        extent.x >= extent.y && extent.x >= extent.z
        ? 0 : extent.y >= extent.z ? 1 : 2
      if extent[axis] > 0 {
        var slice = UnsafeMutableBufferPointer(rebasing: primitives[range])
        slice.sort {
          ($0.centroid[axis], $0.index) < ($1.centroid[axis], $1.index)
        }
      }
      let middle = range.lowerBound + range.count / 2
      return .split(
        middle: middle, axis: axis,
        left: Summary(primitives, range.lowerBound..<middle),
        right: Summary(primitives, middle..<range.upperBound))
    }

    /// Moves the primitives in bins below `firstRight` to the front of the
    /// range and returns where the rest begin, in the order a two-pointer
    /// scan leaves them: the k-th primitive of the right side from the
    /// front swapped with the k-th of the left side from the back.
    ///
    /// Those pairs are found without a branch: where the sides meet is
    /// known from the bins' counts, so the right side's primitives before
    /// it and the left side's after it are collected, then swapped. The
    /// scan's branch on each primitive's side, mispredicted about half the
    /// time on random input, made it the costliest loop of the build.
    mutating func partition(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ range: Range<Int>,
      axis: Int, origin: Scalar, scale: Scalar, bins binCount: Int,
      firstRight: Int
    ) -> Int {
      var leftCount = 0
      for bin in 0..<firstRight { leftCount += bins[bin].count }
      let middle = range.lowerBound + leftCount
      let swaps = Swift.min(leftCount, range.count - leftCount)
      // One more than the pairs: each scan writes a slot past its last
      // find, which the next find would fill.
      if misplaced.count < 2 * swaps + 1 {
        misplaced = [Int32](repeating: 0, count: 2 * swaps + 1)
      }
      return misplaced.withUnsafeMutableBufferPointer { misplaced in
        @inline(__always)
        func isLeft(_ index: Int) -> Int {
          Self.bin(primitives[index].centroid[axis], origin, scale, binCount)
            < firstRight ? 1 : 0
        }
        var front = 0
        for index in range.lowerBound..<middle {
          misplaced[front] = Int32(truncatingIfNeeded: index)
          front += 1 - isLeft(index)
        }
        var back = 0
        for index in stride(from: range.upperBound - 1, through: middle, by: -1) {
          misplaced[swaps + back] = Int32(truncatingIfNeeded: index)
          back += isLeft(index)
        }
        assert(front == back && front <= swaps)
        for pair in 0..<front {
          primitives.swapAt(Int(misplaced[pair]), Int(misplaced[swaps + pair]))
        }
        return middle
      }
    }
  }

}

// MARK: - Traversal

/// The primitives in a hierarchy's leaves, as one ray tests them: a
/// concrete type per primitive kind, so that traversal is specialised for
/// each and calls no closure.
protocol LeafPrimitives {
  associatedtype Scalar: RayScalar
  /// The hit t in (0, tMax) of the primitive at `position`, or nil.
  func intersect(_ position: Int, before tMax: Scalar) -> Scalar?
}

/// Spheres as a kernel stores them, tested against one camera ray.
struct SphereLeaves<Kernel: IntersectionKernel>: LeafPrimitives {
  typealias Scalar = Kernel.Scalar
  let records: UnsafeBufferPointer<Kernel.SphereRecord>
  let ray: CameraRay<Kernel.Scalar>

  @inline(__always)
  func intersect(_ position: Int, before tMax: Scalar) -> Scalar? {
    Kernel.intersect(records[position], ray, before: tMax)
  }
}

extension BoundingVolumeHierarchy {
  /// The nearest sphere hit in (0, tMax): its t and its position in
  /// `records`, which must be stored in `order`.
  ///
  /// Equal to testing every sphere in the original order with a strict
  /// `<`, ties included (see the type's documentation).
  func nearest<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Scalar>, before tMax: Scalar,
    records: UnsafeBufferPointer<Kernel.SphereRecord>, kernel: Kernel.Type
  ) -> (t: Scalar, index: Int)? where Kernel.Scalar == Scalar {
    nearest(ray, before: tMax, leaves: SphereLeaves<Kernel>(records: records, ray: ray))
  }

  /// The nearest hit in (0, tMax) among primitives tested by `leaves`,
  /// stored in `order`: its t and its position.
  func nearest<Leaves: LeafPrimitives>(
    _ ray: CameraRay<Scalar>, before tMax: Scalar, leaves: Leaves
  ) -> (t: Scalar, index: Int)? where Leaves.Scalar == Scalar {
    guard !nodes.isEmpty else { return nil }
    let slab = Slab(ray)
    var tBest = tMax
    // The bound handed to the kernel: tMax until a hit, then just above
    // the best t, so that a sphere at the same t comes back for the tie.
    var limit = tMax
    var best = -1
    var bestOriginal = Int32.max
    // The stack lives in the frame, uninitialised: 64 node indices (256
    // bytes) and 64 entry distances (at most 1 KiB, for Float80), each
    // within the 1 KiB that withUnsafeTemporaryAllocation always places on
    // the stack, so there is no allocation. A tuple did the same, but
    // zeroing it cost about 10 ns a ray, a third of the hierarchy's cost in
    // a scene of 16 spheres.
    withUnsafeTemporaryAllocation(
      of: Int32.self, capacity: Self.stackCapacity
    ) { stackNodes in
      withUnsafeTemporaryAllocation(
        of: Scalar.self, capacity: Self.stackCapacity
      ) { stackEntries in
        nodes.withUnsafeBufferPointer { nodes in
          order.withUnsafeBufferPointer { order in
            guard slab.entry(nodes[0], before: tBest) != nil else { return }
            var current = 0
            var top = 0
            while true {
              let node = nodes[current]
              if node.isLeaf {
                let first = Int(node.index)
                for position in first..<(first + Int(node.count)) {
                  guard let t = leaves.intersect(position, before: limit)
                  else { continue }
                  let original = order[position]
                  if t < tBest || (t == tBest && original < bestOriginal) {
                    tBest = t
                    limit = t.nextUp
                    best = position
                    bestOriginal = original
                  }
                }
              } else {
                let left = Int(node.index)
                let (near, far) =
                  slab.isNegative(node.axis)
                  ? (left + 1, left) : (left, left + 1)
                let nearEntry = slab.entry(nodes[near], before: tBest)
                if let farEntry = slab.entry(nodes[far], before: tBest) {
                  if nearEntry != nil {
                    // At most one entry per level: depth < stackCapacity,
                    // checked when built, bounds `top`.
                    stackNodes[top] = Int32(truncatingIfNeeded: far)
                    stackEntries[top] = farEntry
                    top += 1
                    current = near
                  } else {
                    current = far
                  }
                  continue
                }
                if nearEntry != nil {
                  current = near
                  continue
                }
              }
              // Pop the next box still entered no later than the best hit.
              var next = -1
              while top > 0 {
                top -= 1
                if slab.reaches(stackEntries[top], before: tBest) {
                  next = Int(stackNodes[top])
                  break
                }
              }
              guard next >= 0 else { return }
              current = next
            }
          }
        }
      }
    }
    return best >= 0 ? (tBest, best) : nil
  }

  /// The per-ray part of the ray–box test.
  struct Slab {
    var origin: Vector3<Scalar>
    var inverse: Vector3<Scalar>
    var negative: (Bool, Bool, Bool)

    /// 1 + 2γ₃: (plane − origin)·(1/d) rounds three times, so a computed
    /// distance is within γ₃ of the exact one relative to itself, and an
    /// exit scaled by this is never below an entry that exactly precedes
    /// it (Ize 2013).
    static var exitScale: Scalar { 1 + 2 * BoundingVolumeHierarchy.gamma(3) }

    @inline(__always)
    init(_ ray: CameraRay<Scalar>) {
      origin = ray.origin
      // Computed here, not per camera ray: scenes without a hierarchy never
      // pay the three divisions.
      let direction = ray.direction
      inverse = Vector3(1 / direction.x, 1 / direction.y, 1 / direction.z)
      // The sign bit, so that −0 (inverse −∞) counts as negative.
      negative = (
        inverse.x.sign == .minus, inverse.y.sign == .minus,
        inverse.z.sign == .minus
      )
    }

    @inline(__always)
    func isNegative(_ axis: Int) -> Bool {
      axis == 0 ? negative.0 : axis == 1 ? negative.1 : negative.2
    }

    /// Where the ray enters the node's box, if it does so in (0, bound],
    /// allowing for rounding; nil if it certainly does not.
    @inline(__always)
    func entry(_ node: Node, before bound: Scalar) -> Scalar? {
      let (lower, upper) = (node.lower, node.upper)
      // Near and far planes chosen by the direction's sign rather than by
      // min/max of the two distances: a NaN (0·∞, origin in the plane of a
      // face the ray runs parallel to) then fails the comparisons below and
      // is ignored, leaving the slab unbounded on that side.
      let nearX = ((negative.0 ? upper.x : lower.x) - origin.x) * inverse.x
      let farX = ((negative.0 ? lower.x : upper.x) - origin.x) * inverse.x
      let nearY = ((negative.1 ? upper.y : lower.y) - origin.y) * inverse.y
      let farY = ((negative.1 ? lower.y : upper.y) - origin.y) * inverse.y
      let nearZ = ((negative.2 ? upper.z : lower.z) - origin.z) * inverse.z
      let farZ = ((negative.2 ? lower.z : upper.z) - origin.z) * inverse.z
      var enter: Scalar = 0
      if nearX > enter { enter = nearX }
      if nearY > enter { enter = nearY }
      if nearZ > enter { enter = nearZ }
      var exit = bound
      if farX < exit { exit = farX }
      if farY < exit { exit = farY }
      if farZ < exit { exit = farZ }
      return enter <= exit * Self.exitScale ? enter : nil
    }

    /// Whether a box entered at `entry` can still hold a hit at or before
    /// `bound`.
    @inline(__always)
    func reaches(_ entry: Scalar, before bound: Scalar) -> Bool {
      entry <= bound * Self.exitScale
    }
  }
}
