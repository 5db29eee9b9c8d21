import Dispatch
import Geometry
import SceneDescription
import PlatformSupport

extension BoundingVolumeHierarchy {
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

    /// Builds over `primitives` in `parts` parts (`parts(_:concurrentFrom:
    /// threads:)`): the root's bins in that many, the root's two subtrees
    /// on two threads, where there are several.
    mutating func build(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, summary: Summary,
      parts: Int
    ) {
      guard !primitives.isEmpty else { return }
      nodes.reserveCapacity(2 * primitives.count - 1)
      nodes.append(Self.placeholder)
      var root = Task(
        node: 0, range: primitives.indices, summary: summary, depth: 0)
      guard parts > 1 else {
        grow(primitives, from: root)
        return
      }
      // The root's bins and the root here, then each child's subtree on its
      // own thread into its own array, its root at 0.
      root.binned = binInParts(primitives, summary, parts: parts)
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

    /// Fills `bins` for the root as `bestBinnedSplit` would, each of
    /// `parts` consecutive parts of the primitives on its own thread; the
    /// parts' bins are merged in order (a minimum keeps the first of equal
    /// values and a maximum the last, as one pass does), so they are the
    /// bins one pass gives, whatever the parts. False when the root is not
    /// binned.
    mutating func binInParts(
      _ primitives: UnsafeMutableBufferPointer<Primitive>, _ summary: Summary,
      parts partCount: Int
    ) -> Bool {
      guard primitives.count > 1,
        BoundingVolumeHierarchy.forcedMedianDepth > 0,
        let binning = Binning(summary.centroids, primitives: primitives.count)
      else { return false }
      let empty = [Bin](repeating: Bin(), count: binning.count)
      var parts = [[Bin]](repeating: empty, count: partCount)
      parts.withUnsafeMutableBufferPointer { parts in
        let shared = Shared((primitives, parts))
        Parallel.inParts(primitives.count, partCount) { part, range in
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
  }

}
