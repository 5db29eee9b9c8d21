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
    }
  }

  /// What a camera ray hit first.
  public enum Nearest: Sendable {
    case sphere(Int)
    case plane(Int)
  }

  /// The nearest hit in (0, ∞) of a camera ray through the eye.
  func nearest(_ ray: CameraRay<Scalar>) -> (t: Scalar, what: Nearest)? {
    var tBest = Scalar.infinity
    var best: Nearest?
    if let hierarchy {
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
