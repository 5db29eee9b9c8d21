/// A scene flattened for one camera, one precision and one intersection
/// method: concrete arrays per primitive kind that the loop walks without
/// dynamic dispatch. Built once per render; a scene with no planes has an
/// empty plane array and its loop never enters the plane test.
public struct CompiledScene<Kernel: IntersectionKernel>: Sendable {
  public typealias Scalar = Kernel.Scalar

  public let camera: PerspectiveCamera<Scalar>
  public let rayOrigin: Vector3<Scalar>
  public let eye: Vector3<Scalar>
  var spheres: [Kernel.SphereRecord]
  var sphereMaterials: [Int32]
  var planes: [Kernel.PlaneRecord]
  var planeMaterials: [Int32]
  /// Nil for scenes small enough that testing every sphere is faster.
  var hierarchy: BoundingVolumeHierarchy<Scalar>?
  /// Without a hierarchy: per sphere, the centre relative to the rays'
  /// origin and the distance from it within which the kernel can report a
  /// hit (the hierarchy's conservative reach), for culling spheres per
  /// tile of pixels.
  var cullCenters: [Vector3<Double>] = []
  var cullRadii: [Double] = []
  public let materials: [Material<Scalar>]
  public let lights: [Light<Scalar>]
  public let ambient: RGB<Scalar>
  public let background: RGB<Scalar>

  public var sphereCount: Int { spheres.count }
  public var planeCount: Int { planes.count }
  public var usesHierarchy: Bool { hierarchy != nil }

  /// - Parameter hierarchyThreshold: the sphere count from which a BVH is
  ///   built (see `BoundingVolumeHierarchy.defaultThreshold`).
  public init(
    _ scene: Scene, kernel: Kernel.Type = Kernel.self,
    hierarchyThreshold: Int = BoundingVolumeHierarchy<Scalar>.defaultThreshold
  ) {
    let eyeDouble = scene.camera.center
    camera = PerspectiveCamera(scene.camera)
    eye = Vector3(eyeDouble)
    rayOrigin = Kernel.frameOrigin(eye: eyeDouble)
    let (sphereList, planeList) = scene.root.primitives()
    spheres = sphereList.map { Kernel.makeSphere($0, eye: eyeDouble) }
    sphereMaterials = sphereList.map { Int32(truncatingIfNeeded: $0.materialIndex) }
    planes = planeList.map { Kernel.makePlane($0, eye: eyeDouble) }
    planeMaterials = planeList.map { Int32(truncatingIfNeeded: $0.materialIndex) }
    materials = scene.materials.map(Material.init)
    lights = scene.lights.map(Light.init)
    ambient = Vector3(scene.ambient)
    background = Vector3(scene.background)
    if spheres.count >= hierarchyThreshold {
      let bvh = BoundingVolumeHierarchy(
        spheres: spheres, kernel: Kernel.self, rayOrigin: rayOrigin)
      spheres = bvh.order.map { spheres[Int($0)] }
      sphereMaterials = bvh.order.map { sphereMaterials[Int($0)] }
      hierarchy = bvh
    } else {
      let model: BoundingVolumeHierarchy<Scalar>.ErrorModel =
        Kernel.self == StableKernel<Scalar>.self ? .cancellationFree : .textbook
      for record in spheres {
        let (center, radius) = Kernel.centerAndRadius(record)
        let offset = center - rayOrigin
        let reach = BoundingVolumeHierarchy<Scalar>.reach(
          radius: radius.magnitude, distance: offset.length * (1 + 8 * Scalar.ulpOfOne),
          model: model)
        cullCenters.append(Vector3<Double>(offset))
        cullRadii.append(Double(reach))
      }
    }
  }

  /// Writes into `candidates`, in scene order, the spheres that some ray
  /// through the pyramid from the rays' origin spanned by `corners` (unit
  /// directions in order around it) may hit, and returns their count.
  ///
  /// A sphere is left out only when its reach lies wholly outside one of
  /// the pyramid's faces by more than the rounding of any pixel's ray
  /// (64 ε of the render's precision times the distance), so the nearest
  /// hit of every ray in the tile is the same as testing every sphere.
  func cullSpheres(
    corners: [Vector3<Double>], into candidates: UnsafeMutableBufferPointer<Int32>
  ) -> Int {
    var faces: [Vector3<Double>] = []
    let middle = corners.reduce(Vector3<Double>.zero, +)
    for index in corners.indices {
      let normal = corners[index].cross(corners[(index + 1) % corners.count])
      let length = normal.length
      guard length > 1e-300, length.isFinite else { continue }
      var unit = normal / length
      if unit.dot(middle) < 0 { unit = -unit }
      faces.append(unit)
    }
    let slack = 64 * Double(Scalar.ulpOfOne)
    var count = 0
    for sphere in cullCenters.indices {
      let center = cullCenters[sphere]
      let radius = cullRadii[sphere]
      let margin = radius + slack * (center.length + radius) + 1e-300
      let outside = faces.contains { $0.dot(center) < -margin }
      if !outside {
        candidates[count] = Int32(truncatingIfNeeded: sphere)
        count += 1
      }
    }
    return count
  }

  /// Whether per-tile culling applies: spheres without a hierarchy.
  var cullsPerTile: Bool { hierarchy == nil && spheres.count > 1 }

  /// What a camera ray hit first.
  public enum Nearest: Sendable {
    case sphere(Int)
    case plane(Int)
  }

  /// The nearest hit in (0, ∞) of a camera ray through the eye, testing
  /// only the spheres in `candidates` when given (see `cullSpheres`).
  func nearest(
    _ ray: CameraRay<Scalar>, candidates: UnsafeBufferPointer<Int32>? = nil
  ) -> (t: Scalar, what: Nearest)? {
    var tBest = Scalar.infinity
    var best: Nearest?
    if let candidates {
      spheres.withUnsafeBufferPointer { records in
        for candidate in candidates {
          let index = Int(candidate)
          if let t = Kernel.intersect(records[index], ray, before: tBest) {
            tBest = t
            best = .sphere(index)
          }
        }
      }
    } else if let hierarchy {
      spheres.withUnsafeBufferPointer { records in
        if let hit = hierarchy.nearest(ray, before: tBest, records: records, kernel: Kernel.self) {
          tBest = hit.t
          best = .sphere(hit.index)
        }
      }
    } else {
      spheres.withUnsafeBufferPointer { records in
        for index in records.indices {
          if let t = Kernel.intersect(records[index], ray, before: tBest) {
            tBest = t
            best = .sphere(index)
          }
        }
      }
    }
    for index in planes.indices {
      if let t = Kernel.intersect(planes[index], ray, before: tBest) {
        tBest = t
        best = .plane(index)
      }
    }
    guard let best else { return nil }
    return (tBest, best)
  }

  func normal(of what: Nearest, _ ray: CameraRay<Scalar>, t: Scalar) -> Vector3<Scalar> {
    switch what {
    case .sphere(let index): Kernel.normal(spheres[index], ray, t: t)
    case .plane(let index): Kernel.normal(planes[index])
    }
  }

  func material(of what: Nearest) -> Material<Scalar> {
    let index: Int32
    switch what {
    case .sphere(let sphere): index = sphereMaterials[sphere]
    case .plane(let plane): index = planeMaterials[plane]
    }
    return materials[Int(index)]
  }
}
