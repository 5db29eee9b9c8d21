import FastKernels
import Geometry
import SceneDescription

/// Triangles much larger than their distance from the eye (`TrianglePlane`):
/// kept after the others in `triangles`, outside the hierarchy, and tested
/// one by one with t from their plane, so that the search of every other
/// triangle runs as it did before they existed.
extension CompiledScene {
  /// A large triangle as compiled: its record, its shading and its plane.
  typealias LargeTriangle = (
    record: TriangleRecord<Scalar>, shading: TriangleShading<Scalar>,
    plane: LargeTrianglePlane<Scalar>
  )

  /// Appends the large triangles after the ordinary ones (and after the
  /// hierarchy is built over those).
  mutating func appendLargeTriangles(_ large: [LargeTriangle]) {
    ordinaryTriangleCount = triangles.count
    if !exactPlaneIndices.isEmpty {
      exactPlaneIndices += repeatElement(-1, count: large.count)
    }
    for (record, shading, plane) in large {
      appendTriangle(record, shading)
      trianglePlanes.append(plane)
    }
  }

  /// Large triangles from which the search without tiles finds them
  /// through a hierarchy of their own rather than one by one. Above a few,
  /// they are as many as a mesh has triangles whose planes pass near the
  /// eye: 661 of the 10⁶-triangle mesh, each tested with an exact plane,
  /// made a ray take 7.8 µs (docs/PERFORMANCE.md,
  /// "Hierarchies").
  static var largeTriangleHierarchyThreshold: Int { 8 }

  /// Builds the large triangles' hierarchy when they are many, leaving
  /// them where they are: its leaves reach them through its `order`.
  ///
  /// A hit is within the watertight test's reach of the triangle
  /// (`trianglePad`, 4 ε of the largest coordinate relative to the eye,
  /// M), and t from the plane within a few ulps of where the ray meets
  /// the plane: the point is inside the triangle's box, and t ≤ √3 M. The
  /// boxes are padded by 16 pads, 64 ε M, which holds both with room.
  mutating func buildLargeTriangleHierarchy() {
    let first = ordinaryTriangleCount
    let count = triangles.count - first
    guard count >= Self.largeTriangleHierarchyThreshold else { return }
    let bvh = triangles.withUnsafeBufferPointer { records in
      BoundingVolumeHierarchy<Scalar>(count: count, threads: threads) {
        Self.largeTriangleBox(records[first + $0])
      }
    }
    largeTriangleHierarchy = bvh
    wideLargeTriangleHierarchy = WideHierarchy(bvh, rayOrigin: rayOrigin)
  }

  /// A large triangle's box in its hierarchy.
  @inline(__always)
  static func largeTriangleBox(_ record: TriangleRecord<Scalar>)
    -> (lower: Vector3<Scalar>, upper: Vector3<Scalar>)
  {
    box(record, pad: 16 * trianglePad(record))
  }

  /// Offers the large triangles' hits to `nearest`: the hierarchy's
  /// nearest, first in order among equal t, when there is one (the answer
  /// of testing each in order with a strict `<`), else each in order.
  @inline(__always)
  func testLargeTriangles(
    _ ray: CameraRay<Scalar>, _ prepared: WatertightRay<Scalar>,
    _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    if largeTriangleHierarchy != nil {
      searchLargeTriangles(ray, prepared, &nearest)
      return
    }
    let first = ordinaryTriangleCount
    triangles.withUnsafeBufferPointer { records in
      trianglePlanes.withUnsafeBufferPointer { planes in
        for offset in planes.indices {
          nearest.test(.triangle(first + offset)) {
            TriangleRecord.t(
              prepared, records.baseAddress! + first + offset,
              plane: planes[offset], before: $0)
          }
        }
      }
    }
  }
}

/// A large triangle's plane seen from the eye (`TrianglePlane`), as its
/// test reads it.
struct LargeTrianglePlane<Scalar: RayScalar>: Sendable {
  /// The plane, known beyond the render's precision
  /// (`TrianglePlane.exact`).
  var plane: TrianglePlane.Exact<Scalar>
  /// Whether the watertight test's edge functions alone decide the hit
  /// (`TriangleIntersection.covers`), without the t the plane replaces:
  /// when every vertex coordinate relative to the eye is at most
  /// c = 2^(E/3 − 3) (E the largest exponent: 2^39 in float, 2^338 in
  /// double), a camera ray (|d| = 1 within a few ulps, so |shear| ≤ 1 and
  /// |1/d_z| < 2) gives sheared coordinates below 2c, edge functions below
  /// 8c², terms of the weighted sum of z below 16c³ and their sum below
  /// 48c³ < 2^(E−3): nothing overflows, nothing is NaN, and t, a weighted
  /// mean of the z values, is finite. So `intersect` on the whole line
  /// returns a hit exactly when `covers` is true, and the test saves its
  /// sum and division. Beyond c (never, for a scene within
  /// `LengthScale`'s window) the whole test runs as before.
  var edgesDecide: Bool

  /// `plane` for a triangle whose vertices relative to the eye are
  /// `relative`.
  init(
    _ plane: TrianglePlane.Exact<Scalar>,
    relative: (Vector3<Scalar>, Vector3<Scalar>, Vector3<Scalar>)
  ) {
    self.plane = plane
    let extent = Swift.max(
      relative.0.maxMagnitude, relative.1.maxMagnitude,
      relative.2.maxMagnitude)
    let limit = Scalar(
      sign: .plus,
      exponent: Scalar.greatestFiniteMagnitude.exponent / 3 - 3,
      significand: 1)
    edgesDecide = extent <= limit
  }
}

extension CompiledScene {
  /// `testLargeTriangles` through their hierarchy. Out of line, as the
  /// ellipsoids' is: the traversal inlined into every ray's search is
  /// code that scenes without many large triangles would carry.
  @inline(never)
  func searchLargeTriangles(
    _ ray: CameraRay<Scalar>, _ prepared: WatertightRay<Scalar>,
    _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    guard let hierarchy = largeTriangleHierarchy else { return }
    let first = ordinaryTriangleCount
    triangles.withUnsafeBufferPointer { records in
      trianglePlanes.withUnsafeBufferPointer { planes in
        hierarchy.order.withUnsafeBufferPointer { order in
          let leaves = LargeTriangleLeaves(
            records: records.baseAddress! + first, planes: planes,
            order: order, ray: prepared)
          if let hit = hierarchy.nearest(
            ray, before: nearest.t, leaves: leaves,
            wide: wideLargeTriangleHierarchy)
          {
            nearest.test(.triangle(first + Int(order[hit.index]))) { _ in
              hit.t
            }
          }
        }
      }
    }
  }
}

/// The large triangles as their hierarchy's leaves reach them: position p
/// is large triangle `order[p]`, tested against one prepared ray.
struct LargeTriangleLeaves<Scalar: RayScalar>: LeafPrimitives {
  let records: UnsafePointer<TriangleRecord<Scalar>>
  let planes: UnsafeBufferPointer<LargeTrianglePlane<Scalar>>
  let order: UnsafeBufferPointer<Int32>
  let ray: WatertightRay<Scalar>

  @inline(__always)
  func intersect(_ position: Int, before tMax: Scalar) -> Scalar? {
    let offset = Int(order[position])
    return TriangleRecord.t(
      ray, records + offset, plane: planes[offset], before: tMax)
  }
}
