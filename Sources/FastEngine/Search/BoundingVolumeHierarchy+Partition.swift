import Geometry
import SceneDescription
import PlatformSupport

/// A node's primitives divided between its children: the bins' index of a
/// centroid, the median split, and the partition by bins.
extension BoundingVolumeHierarchy.Builder {
  typealias Primitive = BoundingVolumeHierarchy.Primitive
  typealias Summary = BoundingVolumeHierarchy.Summary

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
