/// A binary tree of boxes over a list of objects' boxes (a mesh's
/// triangles, a large group's objects): each node's box holds its
/// children's, each leaf names a few objects, and a ray visits only the
/// nodes whose boxes it meets.
///
/// Built by splitting the objects at the median of their centres along the
/// widest axis, until at most `leafSize` remain; about 2n/`leafSize` nodes.
public struct BoxHierarchy: Sendable {
  @usableFromInline struct Node: Sendable {
    @usableFromInline var box: BoundingBox
    /// A leaf: its objects are `order[first..<first + count]`. Otherwise
    /// (count 0) its children are the nodes `first` and `first + 1`.
    @usableFromInline var first: Int
    @usableFromInline var count: Int
  }

  @usableFromInline var nodes: [Node] = []
  /// The objects' indices, leaf by leaf.
  @usableFromInline var order: [Int]
  private static let leafSize = 4

  public init(boxes: [BoundingBox]) {
    order = Array(boxes.indices)
    guard !boxes.isEmpty else { return }
    let centers = boxes.map(\.center)
    nodes.append(Node(box: boxes[0], first: 0, count: boxes.count))
    var pending = [0]
    while let index = pending.popLast() {
      let (first, count) = (nodes[index].first, nodes[index].count)
      // A copy: a slice would keep `order`'s storage shared, and the
      // replacement below would copy all of it at every node.
      let members = Array(order[first..<first + count])
      var box = boxes[members.first!]
      var centerBox = BoundingBox(lower: centers[members.first!],
        upper: centers[members.first!])
      for member in members {
        box = box.union(boxes[member])
        centerBox.formUnion(centers[member])
      }
      nodes[index].box = box
      guard count > Self.leafSize else { continue }
      // Split at the median centre along the axis the centres spread most.
      let extent = centerBox.upper - centerBox.lower
      let axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z
        ? 1 : 2
      let sorted = members.sorted { centers[$0][axis] < centers[$1][axis] }
      order.replaceSubrange(first..<first + count, with: sorted)
      let half = count / 2
      nodes[index].first = nodes.count
      nodes[index].count = 0
      nodes.append(Node(box: box, first: first, count: half))
      nodes.append(Node(box: box, first: first + half, count: count - half))
      pending += [nodes.count - 2, nodes.count - 1]
    }
  }

  /// The box of everything, or nil for no objects.
  public var bounds: BoundingBox? { nodes.first?.box }

  /// Calls `body` with every object whose leaf's box the ray meets in
  /// (0, `limit()`), `limit` asked again at each node, as the nearest hit
  /// so far shrinks it.
  @inlinable
  public func forEachCandidate(
    _ ray: Ray<Double>, before limit: () -> Double, _ body: (Int) -> Void
  ) {
    guard !nodes.isEmpty else { return }
    let reciprocal = Vector3(
      1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z)
    // The nodes to visit, on the thread's stack: median splits make at
    // most log₂ n < Int.bitWidth levels, one pending node each, plus two.
    withUnsafeTemporaryAllocation(
      of: Int.self, capacity: Int.bitWidth + 2
    ) { stack in
      var count = 1
      stack[0] = 0
      while count > 0 {
        count -= 1
        let node = nodes[stack[count]]
        guard
          node.box.isHit(
            by: ray, reciprocal: reciprocal, after: 0, before: limit())
        else { continue }
        if node.count > 0 {
          // By position: a slice would count a reference every ray shares.
          for position in node.first..<node.first + node.count {
            body(order[position])
          }
        } else {
          stack[count] = node.first
          stack[count + 1] = node.first + 1
          count += 2
        }
      }
    }
  }
}
