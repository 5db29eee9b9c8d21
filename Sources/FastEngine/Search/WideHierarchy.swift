import Geometry
import SceneDescription
import PlatformSupport

/// A `BoundingVolumeHierarchy` regrouped four children to a node, with the
/// children's boxes stored side by side in Float relative to the rays'
/// origin, so that one ray tests four boxes with a handful of 4-wide
/// instructions (SSE in the baseline x86-64 instruction set, NEON on arm64)
/// and the tree is half as deep.
///
/// It answers exactly as the binary hierarchy does, and so exactly as
/// testing every primitive does (the same t bit for bit, the same primitive,
/// ties included), because it only decides which boxes to open and its box
/// test never rejects a box the ray meets:
/// - Box faces are rounded outward twice: the difference from the origin in
///   the hierarchy's precision is stepped one ulp out, and its conversion
///   to Float is stepped one Float ulp out when it rounded inward. A box
///   relative to the origin means the slab distance is one product,
///   face · (1/d), with no subtraction to cancel.
/// - That distance carries three roundings (d to Float, its reciprocal, the
///   product): within γ₃ of the exact distance to the rounded-out face,
///   relative to itself, as long as nothing overflows or underflows. The
///   exit is enlarged by 1 + 8γ₃ and by 2⁻¹⁰⁰ for any underflow (Ize,
///   "Robust BVH ray traversal", JCGT 2013, with Float's γ).
/// - Nothing overflows: the wide hierarchy is built only when every finite
///   face lies within 2⁶⁰ of the origin (`init?` fails otherwise), and it
///   is used only for rays whose direction components are 0 or at least
///   2⁻⁴⁰ in magnitude (`nearest` returns `.unsuitable` otherwise; the
///   caller then asks the binary hierarchy), so |face · (1/d)| < 2¹⁰¹.
///   A zero component gives an infinite reciprocal of the right sign, and
///   the NaN of 0 · ∞ (the origin in a face's plane, the ray parallel to it)
///   is ignored by the comparisons, leaving that slab unbounded.
/// - Ties: boxes entered at the best t so far are still opened, and leaf
///   primitives are asked for hits up to t.nextUp, keeping an equal t only
///   for a lower original index, as the binary traversal does.
///
/// Children are visited nearest entry first; the others wait on a stack of
/// at most 3 per level in the frame, and are skipped when entered beyond the
/// best hit by the time they come up.
struct WideHierarchy<Scalar: RayScalar>: Sendable {
  /// Four children's boxes, axis by axis, and what each child is: a wide
  /// node's index (≥ 0), a leaf (`~(first << 3 | count)`, negative), or
  /// an empty slot (a box from +∞ to −∞, which every ray misses, and 0).
  struct Node: Sendable {
    var lowerX = SIMD4<Float>(repeating: .infinity)
    var lowerY = SIMD4<Float>(repeating: .infinity)
    var lowerZ = SIMD4<Float>(repeating: .infinity)
    var upperX = SIMD4<Float>(repeating: -.infinity)
    var upperY = SIMD4<Float>(repeating: -.infinity)
    var upperZ = SIMD4<Float>(repeating: -.infinity)
    var children = SIMD4<Int32>(repeating: 0)
  }

  /// The results of `nearest`.
  enum Answer {
    case hit(t: Scalar, position: Int)
    case miss
    /// The ray's direction has a component too small for Float's range:
    /// ask the binary hierarchy.
    case unsuitable
  }

  let nodes: [Node]
  /// The root: a wide node or, for a hierarchy of one leaf, that leaf.
  let root: Int32
  /// The binary hierarchy's leaf order, for the ties.
  let order: [Int32]

  /// Finite faces farther than this from the origin keep the binary hierarchy.
  static var coordinateLimit: Scalar { 0x1p60 }
  /// Smaller non-zero direction components are left to the binary hierarchy.
  static var directionFloor: Scalar { 0x1p-40 }
  /// Three levels of three deferred children each, per wide level: the
  /// wide tree is no deeper than the binary one, whose depth is below 64.
  static var stackCapacity: Int { 256 }
  /// 1 + 8γ₃ in Float, rounded up well beyond the three roundings.
  static var exitScale: Float {
    1 + 8 * (3 * Float.ulpOfOne / 2) / (1 - 3 * Float.ulpOfOne / 2)
  }
  static var underflowSlack: Float { 0x1p-100 }

  /// The hierarchy for rays from `rayOrigin` (in the binary hierarchy's
  /// frame), or nil when it is empty or reaches beyond `coordinateLimit`.
  init?(_ binary: BoundingVolumeHierarchy<Scalar>, rayOrigin: Vector3<Scalar>) {
    guard !binary.nodes.isEmpty else { return nil }
    let limit = Self.coordinateLimit
    // Leaf references keep the first primitive in 28 bits.
    guard binary.order.count < 1 << 27 else { return nil }
    func fits(_ value: Scalar) -> Bool {
      !value.isNaN && (value.isInfinite || value.magnitude <= limit)
    }
    for node in binary.nodes {
      let lower = node.lower - rayOrigin
      let upper = node.upper - rayOrigin
      guard fits(lower.x), fits(lower.y), fits(lower.z), fits(upper.x),
        fits(upper.y),
        fits(upper.z)
      else { return nil }
    }
    var wide: [Node] = []
    wide.reserveCapacity(binary.nodes.count / 2 + 1)
    root = binary.nodes.withUnsafeBufferPointer { binaryNodes in
      Self.collapse(0, binaryNodes, rayOrigin: rayOrigin, into: &wide)
    }
    nodes = wide
    order = binary.order
  }

  /// The reference to binary node `index`, its subtree collapsed into
  /// `wide` depth first. A static function with its state passed in: as a
  /// nested function capturing `wide` it paid an exclusivity check on
  /// every access, a tenth of compiling 10⁶ spheres.
  private static func collapse(
    _ index: Int,
    _ binaryNodes: UnsafeBufferPointer<BoundingVolumeHierarchy<Scalar>.Node>,
    rayOrigin: Vector3<Scalar>, into wide: inout [Node]
  ) -> Int32 {
    let node = binaryNodes[index]
    if node.isLeaf { return ~(node.index << 3 | node.count) }
    // Open the child with the largest surface until there are four: the
    // children a ray is likeliest to enter are then tested together.
    var slots = SIMD4<Int32>(node.index, node.index + 1, 0, 0)
    var count = 2
    while count < 4 {
      var opened = -1
      var largest = -Scalar.infinity
      for slot in 0..<count where !binaryNodes[Int(slots[slot])].isLeaf {
        let box = binaryNodes[Int(slots[slot])]
        let size = box.upper - box.lower
        let area = size.x * size.y + size.y * size.z + size.z * size.x
        if opened < 0 || area > largest {
          opened = slot
          largest = area
        }
      }
      guard opened >= 0 else { break }
      let child = binaryNodes[Int(slots[opened])]
      slots[opened] = child.index
      slots[count] = child.index + 1
      count += 1
    }
    let position = wide.count
    wide.append(Node())
    var result = Node()
    for lane in 0..<count {
      let box = binaryNodes[Int(slots[lane])]
      result.lowerX[lane] = roundedDown(box.lower.x - rayOrigin.x)
      result.lowerY[lane] = roundedDown(box.lower.y - rayOrigin.y)
      result.lowerZ[lane] = roundedDown(box.lower.z - rayOrigin.z)
      result.upperX[lane] = roundedUp(box.upper.x - rayOrigin.x)
      result.upperY[lane] = roundedUp(box.upper.y - rayOrigin.y)
      result.upperZ[lane] = roundedUp(box.upper.z - rayOrigin.z)
      result.children[lane] = collapse(
        Int(slots[lane]), binaryNodes, rayOrigin: rayOrigin, into: &wide)
    }
    wide[position] = result
    return Int32(truncatingIfNeeded: position)
  }

  /// A Float at most `value`, which was rounded to nearest from the exact
  /// difference: one ulp down covers that rounding, then Float's.
  static func roundedDown(_ value: Scalar) -> Float {
    let below = value.nextDown
    var narrowed = Float(below)
    if Scalar(narrowed) > below { narrowed = narrowed.nextDown }
    return narrowed
  }

  static func roundedUp(_ value: Scalar) -> Float {
    let above = value.nextUp
    var narrowed = Float(above)
    if Scalar(narrowed) < above { narrowed = narrowed.nextUp }
    return narrowed
  }

  /// The smallest Float at least `value`: the bound boxes are compared with.
  @inline(__always)
  static func bound(_ value: Scalar) -> Float {
    var narrowed = Float(value)
    if Scalar(narrowed) < value { narrowed = narrowed.nextUp }
    return narrowed
  }

  /// The nearest hit in (0, tMax) among the primitives `leaves` tests,
  /// stored in `order`: its t and position.
  @inline(__always)
  func nearest<Leaves: LeafPrimitives>(
    _ ray: CameraRay<Scalar>, before tMax: Scalar, leaves: Leaves
  ) -> Answer where Leaves.Scalar == Scalar {
    let d = ray.direction
    let floor = Self.directionFloor
    guard d.x == 0 || d.x.magnitude >= floor,
      d.y == 0 || d.y.magnitude >= floor,
      d.z == 0 || d.z.magnitude >= floor
    else { return .unsuitable }
    let inverseX = 1 / Float(d.x)
    let inverseY = 1 / Float(d.y)
    let inverseZ = 1 / Float(d.z)
    let (negativeX, negativeY, negativeZ) = (
      inverseX.sign == .minus, inverseY.sign == .minus, inverseZ.sign == .minus
    )
    let scaleX = SIMD4<Float>(repeating: inverseX)
    let scaleY = SIMD4<Float>(repeating: inverseY)
    let scaleZ = SIMD4<Float>(repeating: inverseZ)
    let exitScale = Self.exitScale
    let slack = Self.underflowSlack

    var nearest = NearestHit<Scalar, Int>(before: tMax)
    var bound = Self.bound(tMax)

    withUnsafeTemporaryAllocation(of: Int32.self, capacity: Self.stackCapacity)
    { stackNodes in
      withUnsafeTemporaryAllocation(
        of: Float.self, capacity: Self.stackCapacity
      ) { stackEntries in
        nodes.withUnsafeBufferPointer { nodes in
          order.withUnsafeBufferPointer { order in
            var current = root
            var top = 0
            while true {
              if current < 0 {
                let leaf = ~current
                let first = Int(leaf >> 3)
                for position in first..<(first + Int(leaf & 7)) {
                  guard
                    let t = leaves.intersect(position, before: nearest.limit)
                  else { continue }
                  if nearest.offer(t, position, order: order[position]) {
                    bound = Self.bound(t)
                  }
                }
              } else {
                let node = nodes[Int(current)]
                // Near and far faces by the direction's sign, so that a NaN
                // (0 · ∞) fails the comparisons and drops out.
                let nearX = (negativeX ? node.upperX : node.lowerX) * scaleX
                let farX = (negativeX ? node.lowerX : node.upperX) * scaleX
                let nearY = (negativeY ? node.upperY : node.lowerY) * scaleY
                let farY = (negativeY ? node.lowerY : node.upperY) * scaleY
                let nearZ = (negativeZ ? node.upperZ : node.lowerZ) * scaleZ
                let farZ = (negativeZ ? node.lowerZ : node.upperZ) * scaleZ
                var enter = SIMD4<Float>(repeating: 0)
                enter.replace(with: nearX, where: nearX .> enter)
                enter.replace(with: nearY, where: nearY .> enter)
                enter.replace(with: nearZ, where: nearZ .> enter)
                var exit = SIMD4<Float>(repeating: bound)
                exit.replace(with: farX, where: farX .< exit)
                exit.replace(with: farY, where: farY .< exit)
                exit.replace(with: farZ, where: farZ .< exit)
                let entered = enter .<= exit * exitScale + slack
                if any(entered) {
                  // The entered children sorted by entry, nearest first.
                  var children: (Int32, Int32, Int32, Int32) = (0, 0, 0, 0)
                  var entries: (Float, Float, Float, Float) = (0, 0, 0, 0)
                  var count = 0
                  withUnsafeMutableBytes(of: &children) { childBytes in
                    withUnsafeMutableBytes(of: &entries) { entryBytes in
                      let sortedChildren = childBytes.bindMemory(to: Int32.self)
                      let sortedEntries = entryBytes.bindMemory(to: Float.self)
                      for lane in 0..<4 where entered[lane] {
                        let entry = enter[lane]
                        var slot = count
                        while slot > 0 && sortedEntries[slot - 1] > entry {
                          sortedEntries[slot] = sortedEntries[slot - 1]
                          sortedChildren[slot] = sortedChildren[slot - 1]
                          slot -= 1
                        }
                        sortedEntries[slot] = entry
                        sortedChildren[slot] = node.children[lane]
                        count += 1
                      }
                      var deferred = count - 1
                      while deferred > 0 {
                        stackNodes[top] = sortedChildren[deferred]
                        stackEntries[top] = sortedEntries[deferred]
                        top += 1
                        deferred -= 1
                      }
                      current = sortedChildren[0]
                    }
                  }
                  continue
                }
              }
              // Pop the next child still entered no later than the best hit.
              var found = false
              while top > 0 {
                top -= 1
                if stackEntries[top] <= bound * exitScale + slack {
                  current = stackNodes[top]
                  found = true
                  break
                }
              }
              guard found else { return }
            }
          }
        }
      }
    }
    guard let hit = nearest.hit else { return .miss }
    return .hit(t: hit.t, position: hit.what)
  }
}

extension BoundingVolumeHierarchy {
  /// The nearest hit, from `wide` (this hierarchy regrouped) when it can
  /// answer for this ray, else from this hierarchy: the same answer either way.
  @inline(__always)
  func nearest<Leaves: LeafPrimitives>(
    _ ray: CameraRay<Scalar>, before tMax: Scalar, leaves: Leaves,
    wide: WideHierarchy<Scalar>?
  ) -> (t: Scalar, index: Int)? where Leaves.Scalar == Scalar {
    if let wide {
      switch wide.nearest(ray, before: tMax, leaves: leaves) {
      case .hit(let t, let position): return (t, position)
      case .miss: return nil
      case .unsuitable: break
      }
    }
    return nearest(ray, before: tMax, leaves: leaves)
  }
}
