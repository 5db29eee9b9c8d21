import Geometry
import SceneDescription
import Numerics
import PlatformSupport

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

  /// Offers each large triangle's hit to `nearest`.
  @inline(__always)
  func testLargeTriangles(
    _ ray: WatertightRay<Scalar>, _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    let first = ordinaryTriangleCount
    triangles.withUnsafeBufferPointer { records in
      trianglePlanes.withUnsafeBufferPointer { planes in
        for offset in planes.indices {
          nearest.test(.triangle(first + offset)) {
            TriangleRecord.t(
              ray, records.baseAddress! + first + offset,
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
