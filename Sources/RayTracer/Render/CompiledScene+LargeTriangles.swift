/// Triangles much larger than their distance from the eye (`TrianglePlane`):
/// kept after the others in `triangles`, outside the hierarchy, and tested
/// one by one with t from their plane, so that the search of every other
/// triangle runs as it did before they existed.
extension CompiledScene {
  /// A large triangle as compiled: its record, the scene's triangle (for
  /// its material and texture coordinates) and its plane.
  typealias LargeTriangle = (
    record: TriangleRecord<Scalar>, triangle: Triangle<Double>,
    plane: (normal: Vector3<Scalar>, distance: Scalar)
  )

  /// Appends the large triangles after the ordinary ones (and after the
  /// hierarchy is built over those).
  mutating func appendLargeTriangles(_ large: [LargeTriangle]) {
    ordinaryTriangleCount = triangles.count
    for (record, triangle, plane) in large {
      appendTriangle(record, triangle)
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
