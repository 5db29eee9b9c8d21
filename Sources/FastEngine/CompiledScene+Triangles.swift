import FastKernels
import Geometry
import SceneDescription

/// The ordinary triangles' searches: through their hierarchy, one by one,
/// or projected onto screen tiles (`ScreenTiles`), each pixel's ray then
/// tested only against the triangles whose boxes hold its pixel.
extension CompiledScene {
  /// The count of ordinary triangles from which renders project them onto
  /// screen tiles (`ScreenTiles`) instead of building their hierarchy
  /// (measured: docs/PERFORMANCE.md, "Thresholds").
  package static var triangleProjectionThreshold: Int { 12 }

  /// Builds the BVH over the ordinary triangles and puts them, their
  /// materials, normals and texture coordinates into its order (the large ones
  /// after them stay where they are): at compile time, or when
  /// `ScreenTiles` declines a scene whose triangles overlap too much on
  /// screen.
  mutating func buildTriangleHierarchy() {
    let bvh = triangles.withUnsafeBufferPointer { records in
      BoundingVolumeHierarchy<Scalar>(
        count: ordinaryTriangleCount, threads: threads
      ) {
        Self.box(records[$0], pad: Self.trianglePad(records[$0]))
      }
    }
    bvh.arrange(&triangles)
    triangleSources.arrange(bvh)
    if !exactPlaneIndices.isEmpty { bvh.arrange(&exactPlaneIndices) }
    if !triangleTextureCoordinates.isEmpty {
      bvh.arrange(&triangleTextureCoordinates)
    }
    triangleHierarchy = bvh
    wideTriangleHierarchy = WideHierarchy(bvh, rayOrigin: rayOrigin)
    projectsTriangles = false
    buildLargeTriangleHierarchy()
  }

  /// The box of `record`'s corners, widened by `pad` on every side.
  @inline(__always)
  static func box(_ record: TriangleRecord<Scalar>, pad: Scalar)
    -> (lower: Vector3<Scalar>, upper: Vector3<Scalar>)
  {
    let lower = Vector3(
      Swift.min(record.v0.x, record.v1.x, record.v2.x),
      Swift.min(record.v0.y, record.v1.y, record.v2.y),
      Swift.min(record.v0.z, record.v1.z, record.v2.z))
    let upper = Vector3(
      Swift.max(record.v0.x, record.v1.x, record.v2.x),
      Swift.max(record.v0.y, record.v1.y, record.v2.y),
      Swift.max(record.v0.z, record.v1.z, record.v2.z))
    let padding = Vector3(pad, pad, pad)
    return (lower: lower - padding, upper: upper + padding)
  }

  /// How far outside a triangle the watertight test can report a hit: a
  /// few ulps of its largest coordinate, since the test decides on the
  /// sheared, rounded vertices. The hierarchy's boxes are rounded out by
  /// it on each axis.
  @inline(__always)
  static func trianglePad(_ record: TriangleRecord<Scalar>) -> Scalar {
    4 * Scalar.ulpOfOne
      * Swift.max(
        record.v0.maxMagnitude, record.v1.maxMagnitude, record.v2.maxMagnitude)
  }

  /// The pixels whose rays the watertight test may report hitting the
  /// triangle: those passing within the ball about each corner that holds
  /// its hierarchy box's padding (√3 times the pad, taken as 2), plus the
  /// rounding of a pixel's ray as for spheres (`cullBound`: 64 ε of the
  /// render's precision times the distance). The pixel box's own pad for
  /// rounded screen coordinates already held every hit in the tests
  /// (`TriangleTilesTests`, triangles grazing pixels' rays at a corner);
  /// this reach keeps the argument from resting on that.
  func triangleBox(
    _ record: TriangleRecord<Scalar>, _ projection: ScreenProjection,
    margin: Double
  ) -> PixelBox {
    let origin = Vector3<Double>(rayOrigin)
    let corners = (
      Vector3<Double>(record.v0) - origin, Vector3<Double>(record.v1) - origin,
      Vector3<Double>(record.v2) - origin
    )
    let pad = 2 * Double(Self.trianglePad(record))
    // ‖·‖₁ bounds each corner's distance without a square root.
    func size(_ p: Vector3<Double>) -> Double {
      p.x.magnitude + p.y.magnitude + p.z.magnitude
    }
    let distance = Swift.max(size(corners.0), size(corners.1), size(corners.2))
    let slack = 64 * Double(Scalar.ulpOfOne)
    let reach = pad + slack * (distance + pad) + 1e-300
    return projection.pixelBox(
      triangle: corners.0, corners.1, corners.2, reach: reach, margin: margin)
  }

  /// Offers the ordinary triangles' hits to `nearest`: through the
  /// hierarchy when there is one, else each in order; the leaves that
  /// take some triangles' t from their exact planes only in scenes that
  /// have such triangles.
  @inline(__always)
  func testOrdinaryTriangles(
    _ ray: CameraRay<Scalar>, _ prepared: WatertightRay<Scalar>,
    _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    guard exactPlaneIndices.isEmpty else {
      testPlanedTriangles(ray, prepared, &nearest)
      return
    }
    triangles.withUnsafeBufferPointer { records in
      testTriangles(
        ray, TriangleLeaves(records: records, ray: prepared), &nearest)
    }
  }

  /// `testOrdinaryTriangles` for a scene where some ordinary triangles take
  /// t from their exact planes.
  @inline(never)
  func testPlanedTriangles(
    _ ray: CameraRay<Scalar>, _ prepared: WatertightRay<Scalar>,
    _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    triangles.withUnsafeBufferPointer { records in
      exactPlaneIndices.withUnsafeBufferPointer { indices in
        exactPlanes.withUnsafeBufferPointer { planes in
          testTriangles(
            ray,
            PlanedTriangleLeaves(
              records: records, planeIndices: indices, planes: planes,
              ray: prepared), &nearest)
        }
      }
    }
  }

  /// The ordinary triangles of `leaves` searched through the hierarchy
  /// when there is one, else each in order.
  @inline(__always)
  func testTriangles<Leaves: LeafPrimitives>(
    _ ray: CameraRay<Scalar>, _ leaves: Leaves,
    _ nearest: inout NearestHit<Scalar, Nearest>
  ) where Leaves.Scalar == Scalar {
    if let triangleHierarchy {
      if let hit = triangleHierarchy.nearest(
        ray, before: nearest.t, leaves: leaves, wide: wideTriangleHierarchy)
      {
        nearest.test(.triangle(hit.index)) { _ in hit.t }
      }
    } else {
      for index in 0..<ordinaryTriangleCount {
        nearest.test(.triangle(index)) { leaves.intersect(index, before: $0) }
      }
    }
  }

  /// The exact plane of ordinary triangle `index`, when its t comes from
  /// one.
  @inline(__always)
  func exactPlane(ofTriangle index: Int) -> TrianglePlane.Exact<Scalar>? {
    guard index < exactPlaneIndices.count else { return nil }
    let plane = exactPlaneIndices[index]
    return plane >= 0 ? exactPlanes[Int(plane)] : nil
  }
}
