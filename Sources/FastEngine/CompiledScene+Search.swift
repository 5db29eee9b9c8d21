import FastKernels
import Geometry

/// The nearest hit of one camera ray: the spheres by a search of the
/// render's choice, then planes, triangles, ellipsoids and the other
/// shapes, each kind in scene order (`NearestHit`).
extension CompiledScene {
  /// The nearest hit in (0, ∞) of a camera ray through the eye, its
  /// spheres found by `search`.
  @inline(__always)
  func nearest<Search: NearestSphereSearch>(
    _ ray: CameraRay<Scalar>, by search: Search
  ) -> (t: Scalar, what: Nearest)? {
    nearest(ray, after: search.nearestSphere(ray, in: self))
  }

  /// The nearest hit in (0, ∞) of a camera ray through the eye, by the
  /// hierarchy when the scene has one, else testing every sphere.
  func nearest(_ ray: CameraRay<Scalar>) -> (t: Scalar, what: Nearest)? {
    hierarchy != nil
      ? nearest(ray, by: SphereHierarchy()) : nearest(ray, by: EverySphere())
  }

  /// The search of `nearest` after the spheres, from the nearest sphere
  /// hit (or none): planes, triangles, ellipsoids.
  @inline(__always)
  func nearest(
    _ ray: CameraRay<Scalar>, after spheres: NearestHit<Scalar, Nearest>
  ) -> (t: Scalar, what: Nearest)? {
    var nearest = spheres
    testPlanes(ray, &nearest)
    if triangles.isEmpty {
      testEllipsoids(ray, &nearest)
      return nearest.hit
    }
    testTrianglesAndEllipsoids(ray, &nearest)
    return nearest.hit
  }

  /// The triangles' search, then the ellipsoids': a call of its own, so
  /// that the pixel loop of a scene without triangles (every sphere and
  /// plane scene) does not carry it (inlined, it made the stable method's
  /// sphere scenes 1.17–1.19× naive in double, where they had been
  /// 1.09–1.14×).
  @inline(never)
  func testTrianglesAndEllipsoids(
    _ ray: CameraRay<Scalar>, _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    let prepared = WatertightRay(
      Ray(origin: ray.origin, direction: ray.direction))
    testOrdinaryTriangles(ray, prepared, &nearest)
    testLargeTrianglesAndEllipsoids(ray, prepared, &nearest)
  }

  /// Offers the planes' hits to `nearest`, in order.
  @inline(__always)
  func testPlanes(
    _ ray: CameraRay<Scalar>, _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    for index in planes.indices {
      nearest.test(.plane(index)) {
        Kernel.intersect(planes[index], ray, before: $0)
      }
    }
  }

  /// Offers the hits of what comes after the ordinary triangles in the
  /// search: the large triangles, then the ellipsoids.
  @inline(__always)
  func testLargeTrianglesAndEllipsoids(
    _ ray: CameraRay<Scalar>, _ prepared: WatertightRay<Scalar>,
    _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    if ordinaryTriangleCount < triangles.count {
      testLargeTriangles(ray, prepared, &nearest)
    }
    testEllipsoids(ray, &nearest)
  }

  /// Offers the ellipsoids' hits to `nearest`, through their hierarchy
  /// when there is one (`searchEllipsoids`), else in order; then the other
  /// shapes'. The records are read in place: copied out of the array, the
  /// stable method's (both of its forms, `StableEllipsoid`) made every
  /// test a memory copy.
  @inline(__always)
  func testEllipsoids(
    _ ray: CameraRay<Scalar>, _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    if ellipsoidHierarchy != nil {
      searchEllipsoids(ray, &nearest)
    } else {
      ellipsoids.withUnsafeBufferPointer { records in
        for index in records.indices {
          nearest.test(.ellipsoid(index)) {
            Kernel.intersect(records[index], ray, before: $0)
          }
        }
      }
    }
    if !shapes.isEmpty { testShapes(ray, &nearest) }
  }
}
