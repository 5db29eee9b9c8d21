import Geometry
import SceneDescription

/// The spheres a tile of pixels' rays may hit (`CompiledScene.cullSpheres`),
/// in scene order: for scenes too small for a hierarchy or screen
/// projection.
struct CulledSpheres: NearestSphereSearch {
  let candidates: UnsafeBufferPointer<Int32>

  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    scene.nearestSphere(ray, among: candidates.lazy.map { Int($0) })
  }

  @inline(__always)
  func nearestSphere<Kernel: IntersectionKernel>(
    _ ray: CameraRay<Kernel.Scalar>, in scene: CompiledScene<Kernel>,
    memo: inout Kernel.SphereHitMemo
  ) -> NearestHit<Kernel.Scalar, CompiledScene<Kernel>.Nearest> {
    scene.nearestSphere(
      ray, among: candidates.lazy.map { Int($0) }, memo: &memo)
  }
}

/// Culling per tile: each tile of pixels tests only the spheres its rays
/// may hit.
extension CompiledScene {
  /// Whether per-tile culling applies: spheres without a hierarchy.
  var cullsPerTile: Bool {
    hierarchy == nil && !projectsSpheres && spheres.count > 1
  }

  /// A sphere's centre relative to the rays' origin and the distance from
  /// it that any pixel's ray the kernel reports hitting the sphere comes
  /// within: the hierarchy's reach, plus the rounding of the ray's own
  /// direction (64 ε of the render's precision times the distance).
  @inline(__always)
  func cullBound(_ record: Kernel.SphereRecord) -> (
    center: Vector3<Double>, radius: Double
  ) {
    let model: BoundingVolumeHierarchy<Scalar>.ErrorModel =
      Kernel.self == StableKernel<Scalar>.self ? .cancellationFree : .textbook
    let (center, radius) = Kernel.centerAndRadius(record)
    let offset = center - rayOrigin
    let reach = Double(
      BoundingVolumeHierarchy<Scalar>.reach(
        radius: radius.magnitude,
        distance: offset.length * (1 + 8 * Scalar.ulpOfOne),
        model: model))
    let centre = Vector3<Double>(offset)
    let slack = 64 * Double(Scalar.ulpOfOne)
    return (centre, reach + slack * (centre.length + reach) + 1e-300)
  }

  /// Writes into `candidates`, in scene order, the spheres that some ray
  /// through the pyramid from the rays' origin spanned by `corners` (unit
  /// directions in order around it) may hit, and returns their count.
  ///
  /// A sphere is left out only when its `cullBound` lies wholly outside
  /// one of the pyramid's faces, so the nearest hit of every ray in the
  /// tile is the same as testing every sphere.
  func cullSpheres(
    corners: (
      Vector3<Double>, Vector3<Double>, Vector3<Double>, Vector3<Double>
    ),
    into candidates: UnsafeMutableBufferPointer<Int32>
  ) -> Int {
    // Four faces in a tuple: this runs for every tile, and arrays here
    // were an allocation or two per 64 pixels.
    let middle = corners.0 + corners.1 + corners.2 + corners.3
    func face(_ a: Vector3<Double>, _ b: Vector3<Double>) -> Vector3<Double> {
      let normal = a.cross(b)
      let length = normal.length
      guard length > 1e-300, length.isFinite else { return .zero }
      let unit = normal / length
      return unit.dot(middle) < 0 ? -unit : unit
    }
    let faces = (
      face(corners.0, corners.1), face(corners.1, corners.2),
      face(corners.2, corners.3), face(corners.3, corners.0)
    )
    // A degenerate edge's face is zero, which excludes nothing.
    var count = 0
    for sphere in cullCenters.indices {
      let center = cullCenters[sphere]
      let margin = cullRadii[sphere]
      let outside =
        faces.0.dot(center) < -margin || faces.1.dot(center) < -margin
        || faces.2.dot(center) < -margin || faces.3.dot(center) < -margin
      if !outside {
        candidates[count] = Int32(truncatingIfNeeded: sphere)
        count += 1
      }
    }
    return count
  }
}
