import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension BoundingVolumeHierarchyTests {
  // MARK: - Structure

  /// The layout and containment invariants, for any hierarchy over
  /// `spheres` (in the scene's order).
  func checkStructure<Kernel: IntersectionKernel>(
    _ hierarchy: BoundingVolumeHierarchy<Kernel.Scalar>,
    spheres: [Kernel.SphereRecord], kernel: Kernel.Type,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    typealias BVH = BoundingVolumeHierarchy<Kernel.Scalar>
    let nodes = hierarchy.nodes
    XCTAssertEqual(
      hierarchy.order.sorted(), (0..<Int32(spheres.count)).map { $0 },
      "order is a permutation", file: file, line: line)
    guard !nodes.isEmpty else {
      XCTAssertTrue(spheres.isEmpty, file: file, line: line)
      return
    }
    // Walk depth first, left child first: children must be adjacent and
    // allocated in that order, and the leaves must cover the spheres in
    // order, each exactly once.
    var nextPair = 1
    var nextSphere = 0
    var deepest = 0
    var problems: [String] = []
    var stack = [(node: 0, depth: 0)]
    while let (index, depth) = stack.popLast() {
      let node = nodes[index]
      deepest = max(deepest, depth)
      guard node.lower.x <= node.upper.x, node.lower.y <= node.upper.y,
        node.lower.z <= node.upper.z
      else {
        problems.append("node \(index) has an inverted box")
        continue
      }
      if node.isLeaf {
        if node.count > BVH.maximumLeafSize {
          problems.append("leaf \(index) holds \(node.count)")
        }
        if Int(node.index) != nextSphere {
          problems.append(
            "leaf \(index) starts at \(node.index), not \(nextSphere)")
        }
        for position in Int(node.index)..<Int(node.index + node.count) {
          let (center, radius) = Kernel.centerAndRadius(
            spheres[Int(hierarchy.order[position])])
          // The exact sphere, at least, lies inside its leaf's box.
          let lower = center - Vector3(radius, radius, radius)
          let upper = center + Vector3(radius, radius, radius)
          if !(contains(node, lower: lower, upper: upper)) {
            problems.append("leaf \(index) does not hold sphere at \(position)")
          }
        }
        nextSphere = Int(node.index + node.count)
      } else {
        let first = Int(node.index)
        if first != nextPair || first + 1 >= nodes.count {
          problems.append(
            "node \(index)'s children at \(first), not \(nextPair)")
          continue
        }
        if !(0...2).contains(node.axis) {
          problems.append("node \(index) split on axis \(node.axis)")
        }
        nextPair += 2
        for child in [first, first + 1] {
          let box = nodes[child]
          if !contains(node, lower: box.lower, upper: box.upper) {
            problems.append("node \(index) does not hold child \(child)")
          }
        }
        stack.append((first + 1, depth + 1))
        stack.append((first, depth + 1))
      }
    }
    XCTAssertEqual(
      nextPair, nodes.count, "every node reached", file: file, line: line)
    XCTAssertEqual(
      nextSphere, spheres.count, "every sphere in a leaf", file: file,
      line: line)
    XCTAssertEqual(deepest, hierarchy.depth, file: file, line: line)
    XCTAssertLessThan(deepest, BVH.stackCapacity, file: file, line: line)
    XCTAssertTrue(
      problems.isEmpty, "\(problems.prefix(5))", file: file, line: line)
  }

  /// No part of the box [lower, upper] lies outside the node's; written
  /// with negations so that the NaN bounds of a sphere whose centre
  /// overflowed (∞ − ∞) are vacuously held.
  func contains<T: RayScalar>(
    _ node: BoundingVolumeHierarchy<T>.Node, lower: Vector3<T>,
    upper: Vector3<T>
  ) -> Bool {
    !(lower.x < node.lower.x || lower.y < node.lower.y
      || lower.z < node.lower.z || upper.x > node.upper.x
      || upper.y > node.upper.y || upper.z > node.upper.z)
  }

  /// The same input gives the same tree, whether the two halves are built
  /// on two threads or one after the other.
  func testBuild_IsDeterministic_ConcurrentOrNot() {
    var generator = SplitMix64(seed: 0xDE7)
    let boxes = (0..<6000).map {
      _ -> (lower: Vector3<Float>, upper: Vector3<Float>) in
      let center = Vector3<Float>(
        generator.unitVector(Double.self) * generator.logUniform(1, 100))
      let radius: Float = generator.logUniform(0.01, 2)
      return BoundingVolumeHierarchy<Float>.box(
        center: center, radius: radius, rayOrigin: .zero,
        model: .cancellationFree)
    }
    let sequential = BoundingVolumeHierarchy<Float>(
      boxes: boxes, concurrentFrom: .max)
    let concurrent = BoundingVolumeHierarchy<Float>(
      boxes: boxes, concurrentFrom: 1000)
    let again = BoundingVolumeHierarchy<Float>(
      boxes: boxes, concurrentFrom: 1000)
    XCTAssertEqual(sequential.nodes, concurrent.nodes)
    XCTAssertEqual(sequential.order, concurrent.order)
    XCTAssertEqual(sequential.depth, concurrent.depth)
    XCTAssertEqual(concurrent.nodes, again.nodes)
    XCTAssertEqual(concurrent.order, again.order)
  }

  /// The same tree from 1, 2, 3, 7 and 16 threads: the primitives, the
  /// root's bounds and bins in one part per thread (here of at least 500
  /// boxes, so 16 threads make 16 parts), merged in order.
  func testBuild_AnyThreadCount_SameTree() {
    var generator = SplitMix64(seed: 0x7EAD5)
    let boxes = (0..<20_000).map {
      _ -> (lower: Vector3<Double>, upper: Vector3<Double>) in
      let center =
        generator.unitVector(Double.self) * generator.logUniform(1, 100)
      // Some boxes share their bounds, so the merge order of equal values
      // (and of ±0) shows.
      let radius: Double =
        generator.next() % 8 == 0 ? 1 : generator.logUniform(0.01, 2)
      return BoundingVolumeHierarchy<Double>.box(
        center: Vector3(
          center.x.rounded(), center.y.rounded(), center.z.rounded()),
        radius: radius, rayOrigin: .zero, model: .cancellationFree)
    }
    typealias BVH = BoundingVolumeHierarchy<Double>
    let one = BVH(boxes: boxes, concurrentFrom: 1000, threads: 1)
    XCTAssertEqual(
      BVH.parts(boxes.count, concurrentFrom: 1000, threads: 16), 16)
    for threads in runsLongTests ? [2, 3, 7, 16] : [3, 16] {
      let many = BVH(boxes: boxes, concurrentFrom: 1000, threads: threads)
      XCTAssertEqual(many.nodes, one.nodes, "\(threads) threads: nodes")
      XCTAssertEqual(many.order, one.order, "\(threads) threads: order")
      XCTAssertEqual(many.depth, one.depth, "\(threads) threads: depth")
    }
  }

  /// Spheres give the same tree whether their boxes, the root's bounds
  /// and bins and the two subtrees are computed on two threads or one, and
  /// the same as their boxes given directly.
  func testBuildFromSpheres_IsDeterministic_ConcurrentOrNot() {
    typealias Kernel = StableKernel<Double>
    var generator = SplitMix64(seed: 0x5FE)
    let spheres = (0..<5000).map { index -> Sphere<Double> in
      let center =
        generator.unitVector(Double.self) * generator.logUniform(1, 100)
      return Sphere(
        center: center, radius: generator.logUniform(0.01, 2), materialIndex: 0)
    }
    let eye = Vector3<Double>(0, 0, 150)
    let records = spheres.map { Kernel.makeSphere($0, eye: eye) }
    let origin = Kernel.frameOrigin(eye: eye)
    typealias BVH = BoundingVolumeHierarchy<Double>
    let sequential = BVH(
      spheres: records, kernel: Kernel.self, rayOrigin: origin,
      concurrentFrom: .max)
    let concurrent = BVH(
      spheres: records, kernel: Kernel.self, rayOrigin: origin,
      concurrentFrom: 100)
    let boxes = records.map { record in
      let (center, radius) = Kernel.centerAndRadius(record)
      return BVH.box(
        center: center, radius: radius, rayOrigin: origin,
        model: .cancellationFree)
    }
    let fromBoxes = BVH(boxes: boxes, concurrentFrom: .max)
    XCTAssertEqual(sequential.nodes, concurrent.nodes)
    XCTAssertEqual(sequential.order, concurrent.order)
    XCTAssertEqual(sequential.depth, concurrent.depth)
    XCTAssertEqual(sequential.nodes, fromBoxes.nodes)
    XCTAssertEqual(sequential.order, fromBoxes.order)
  }

  /// Binning a range as four blocks gives the bins of one pass bit for bit,
  /// signed zeros included, for every length around the blocks' edges.
  func testFill_FourBlocksGiveTheBinsOfOnePass() {
    typealias BVH = BoundingVolumeHierarchy<Float>
    var generator = SplitMix64(seed: 0xF11)
    // Coordinates from a few values, zeros of both signs among them, so
    // that bins see many equal values.
    let values: [Float] = [-0.0, 0.0, 1, -1, 2.5, 0.0, -0.0]
    func pick() -> Float {
      values[Int(generator.next() % UInt64(values.count))]
    }
    for count in [1, 2, 63, 64, 65, 66, 67, 200, 1001] {
      var primitives = (0..<count).map { index -> BVH.Primitive in
        let lower = Vector3(pick(), pick(), pick())
        let upper = Vector3(
          Swift.max(lower.x, pick()), Swift.max(lower.y, pick()),
          Swift.max(lower.z, pick()))
        return BVH.Primitive(
          lower: lower, upper: upper, index: Int32(index))
      }
      var centroids = BVH.Bounds()
      for primitive in primitives {
        centroids.include(lower: primitive.centroid, upper: primitive.centroid)
      }
      guard let binning = BVH.Binning(centroids, primitives: count) else {
        continue
      }
      var onePass = [BVH.Bin](repeating: BVH.Bin(), count: binning.count)
      var blocks = [BVH.Bin](repeating: BVH.Bin(), count: 4 * binning.count)
      primitives.withUnsafeMutableBufferPointer { primitives in
        onePass.withUnsafeMutableBufferPointer {
          BVH.Builder.fill($0, primitives, primitives.indices, binning)
        }
        blocks.withUnsafeMutableBufferPointer {
          BVH.Builder.fill($0, primitives, primitives.indices, binning)
        }
      }
      func bits(_ bounds: BVH.Bounds) -> [UInt32] {
        [
          bounds.lower.x, bounds.lower.y, bounds.lower.z, bounds.upper.x,
          bounds.upper.y, bounds.upper.z,
        ].map(\.bitPattern)
      }
      for bin in 0..<binning.count {
        XCTAssertEqual(onePass[bin].count, blocks[bin].count, "\(count) \(bin)")
        XCTAssertEqual(
          bits(onePass[bin].summary.bounds), bits(blocks[bin].summary.bounds),
          "\(count) \(bin)")
        XCTAssertEqual(
          bits(onePass[bin].summary.centroids),
          bits(blocks[bin].summary.centroids), "\(count) \(bin)")
      }
    }
  }

  /// The partition leaves the primitives as a two-pointer scan does, for
  /// every boundary between bins and ranges of many lengths.
  func testPartition_MatchesTwoPointerScan() {
    typealias BVH = BoundingVolumeHierarchy<Double>
    var generator = SplitMix64(seed: 0x9A27)
    for count in [2, 3, 5, 17, 100, 1000] {
      let primitives = (0..<count).map { index -> BVH.Primitive in
        let center = Vector3<Double>(
          generator.uniform(-10...10), generator.uniform(-10...10),
          generator.uniform(-10...10))
        let box = Vector3<Double>(0.5, 0.5, 0.5)
        return BVH.Primitive(
          lower: center - box, upper: center + box, index: Int32(index))
      }
      var centroids = BVH.Bounds()
      for primitive in primitives {
        centroids.include(lower: primitive.centroid, upper: primitive.centroid)
      }
      guard let binning = BVH.Binning(centroids, primitives: count) else {
        return XCTFail("\(count) random centroids cannot be binned")
      }
      var builder = BVH.Builder()
      builder.bins.withUnsafeMutableBufferPointer { bins in
        var mutable = primitives
        mutable.withUnsafeMutableBufferPointer {
          BVH.Builder.fill(bins, $0, $0.indices, binning)
        }
      }
      for firstRight in 1..<binning.count {
        func isLeft(_ primitive: BVH.Primitive) -> Bool {
          binning.bin(primitive.centroid) < firstRight
        }
        var expected = primitives
        var low = 0
        var high = count - 1
        while true {
          while low <= high && isLeft(expected[low]) { low += 1 }
          while low < high && !isLeft(expected[high]) { high -= 1 }
          guard low < high else { break }
          expected.swapAt(low, high)
          low += 1
          high -= 1
        }
        var actual = primitives
        let middle = actual.withUnsafeMutableBufferPointer {
          builder.partition(
            $0, $0.indices, axis: binning.axis, origin: binning.origin,
            scale: binning.scale, bins: binning.count, firstRight: firstRight)
        }
        XCTAssertEqual(middle, low, "\(count) \(firstRight)")
        XCTAssertEqual(
          actual.map(\.index), expected.map(\.index), "\(count) \(firstRight)")
      }
    }
  }

  /// Every box holds the sphere with room for the kernel's rounding: more
  /// room for the textbook kernel, whose reach grows with √ε·distance.
  func testBox_HoldsSphereWithRoomForRounding() {
    typealias BVH = BoundingVolumeHierarchy<Float>
    let center = Vector3<Float>(0, 0, -1000)
    let stable = BVH.box(
      center: center, radius: 0.01, rayOrigin: .zero, model: .cancellationFree)
    let textbook = BVH.box(
      center: center, radius: 0.01, rayOrigin: .zero, model: .textbook)
    // The stable reach is r + γ₃₂·(distance + r): 0.01 + 0.002 here.
    XCTAssertGreaterThan(stable.upper.x, 0.011)
    XCTAssertLessThan(stable.upper.x, 0.013)
    // The textbook reach is about √γ₆₄·distance ≈ 2 here, two hundred
    // radii: b² − 4ac carries an error of order γ·|d|²·distance², which is
    // 4a(r² − ℓ²) for ℓ, the ray's distance from the centre, of order
    // √γ·distance.
    XCTAssertGreaterThan(textbook.upper.x, 1.5)
    XCTAssertLessThan(textbook.upper.x, 2.5)
    // A NaN sphere never hits; its box is everything, not NaN.
    let nan = BVH.box(
      center: Vector3(.nan, 0, 0), radius: 1, rayOrigin: .zero,
      model: .cancellationFree)
    XCTAssertEqual(nan.lower.y, -.infinity)
    XCTAssertEqual(nan.upper.x, .infinity)
  }
}
