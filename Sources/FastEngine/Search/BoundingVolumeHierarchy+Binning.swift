import Geometry

// The binned surface-area heuristic's bookkeeping: the boxes, bounds and
// bins a build partitions.

extension BoundingVolumeHierarchy {
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
  /// rendered no faster in the timings behind `defaultThreshold`.
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
}
