import Geometry
import SceneDescription

// Traversal: the nearest hit of one ray, equal to testing every primitive.

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
    nearest(
      ray, before: tMax,
      leaves: SphereLeaves<Kernel>(records: records, ray: ray))
  }

  /// The nearest hit in (0, tMax) among primitives tested by `leaves`,
  /// stored in `order`: its t and its position.
  func nearest<Leaves: LeafPrimitives>(
    _ ray: CameraRay<Scalar>, before tMax: Scalar, leaves: Leaves
  ) -> (t: Scalar, index: Int)? where Leaves.Scalar == Scalar {
    guard !nodes.isEmpty else { return nil }
    let slab = Slab(ray)
    var nearest = NearestHit<Scalar, Int>(before: tMax)
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
            guard slab.entry(nodes[0], before: nearest.t) != nil else {
              return
            }
            var current = 0
            var top = 0
            while true {
              let node = nodes[current]
              if node.isLeaf {
                let first = Int(node.index)
                for position in first..<(first + Int(node.count)) {
                  guard
                    let t = leaves.intersect(position, before: nearest.limit)
                  else { continue }
                  _ = nearest.offer(t, position, order: order[position])
                }
              } else {
                let left = Int(node.index)
                let (near, far) =
                  slab.isNegative(node.axis)
                  ? (left + 1, left) : (left, left + 1)
                let nearEntry = slab.entry(nodes[near], before: nearest.t)
                if let farEntry = slab.entry(nodes[far], before: nearest.t) {
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
                if slab.reaches(stackEntries[top], before: nearest.t) {
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
    return nearest.hit.map { ($0.t, $0.what) }
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
