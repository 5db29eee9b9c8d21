import FastKernels
import Geometry
import SceneDescription
import PlatformSupport

/// A scene flattened for one camera, one precision and one intersection
/// method: concrete arrays per primitive kind that the loop walks without
/// dynamic dispatch. Built once per render; a scene with no planes has an
/// empty plane array and its loop never enters the plane test.
package struct CompiledScene<Kernel: IntersectionKernel>: Sendable {
  package typealias Scalar = Kernel.Scalar

  package let camera: PerspectiveCamera<Scalar>
  /// The eye in the frame of the records, scaled as they are.
  package let rayOrigin: Vector3<Scalar>
  /// The eye in the world, for shading.
  package let eye: Vector3<Scalar>
  /// 2^k: the records hold the scene's lengths times 2^−k, so a search's
  /// t is the world's t times 2^−k, exactly (`LengthScale`); 1 for every
  /// scene within the precision's comfortable range.
  package let lengthScale: Scalar
  var spheres: [Kernel.SphereRecord]
  var sphereMaterials: [Int32]
  var planes: [Kernel.PlaneRecord]
  var planeMaterials: [Int32]
  /// Nil for scenes small enough that testing every sphere is faster.
  var hierarchy: BoundingVolumeHierarchy<Scalar>?
  /// The same hierarchy four-wide, for the rays it can answer.
  var wideHierarchy: WideHierarchy<Scalar>?
  /// Without a hierarchy: per sphere, the centre relative to the rays'
  /// origin and the distance from it within which the kernel can report a
  /// hit (the hierarchy's conservative reach), for culling spheres per
  /// tile of pixels.
  var cullCenters: [Vector3<Double>] = []
  var cullRadii: [Double] = []
  /// Spheres left for the renderer to project onto screen tiles: no
  /// hierarchy, no culling data (see `projectionThreshold`).
  private(set) var projectsSpheres = false
  /// Triangles in the kernel's frame, in hierarchy order when there is one.
  var triangles: [TriangleRecord<Scalar>] = []
  /// Per triangle, the face it was compiled from: its material, and where
  /// its vertex normals are in `vertexNormals`.
  var triangleSources = TriangleSources()
  /// The meshes' normals in the render's precision, shared by their
  /// triangles as in the model.
  var vertexNormals: [Vector3<Scalar>] = []
  /// Per triangle, its texture coordinates: only for textured renders.
  var triangleTextureCoordinates: [Triangle<Scalar>.TextureCoordinates?] = []
  /// The triangles before this index are searched by the watertight
  /// test (through the hierarchy when there is one); those from it on are
  /// large beside their distance from the eye, tested one by one with t
  /// from `trianglePlanes` (`TrianglePlane`).
  var ordinaryTriangleCount = 0
  /// Per large triangle, in order, its plane seen from the eye.
  var trianglePlanes: [LargeTrianglePlane<Scalar>] = []
  /// Per ordinary triangle, the index in `exactPlanes` of the plane its t
  /// comes from, or −1 for the watertight test's t; empty when no
  /// ordinary triangle is thin or large enough to need one
  /// (`TrianglePlane.needsExactT`), so that such scenes search as before.
  var exactPlaneIndices: [Int32] = []
  /// The exact planes of the ordinary triangles that need them.
  var exactPlanes: [TrianglePlane.Exact<Scalar>] = []
  /// Triangles left in order for `ScreenTiles` to project, without a
  /// hierarchy (see `triangleProjectionThreshold`).
  var projectsTriangles = false
  var triangleHierarchy: BoundingVolumeHierarchy<Scalar>?
  var wideTriangleHierarchy: WideHierarchy<Scalar>?
  /// The large triangles' hierarchy, for the search without tiles, when
  /// there are many (`buildLargeTriangleHierarchy`).
  var largeTriangleHierarchy: BoundingVolumeHierarchy<Scalar>?
  var wideLargeTriangleHierarchy: WideHierarchy<Scalar>?
  /// Spheres under transforms that are not similarities.
  var ellipsoids: [Kernel.EllipsoidRecord] = []
  var ellipsoidMaterials: [Int32] = []
  /// The ellipsoids' hierarchy, when there are many
  /// (`buildEllipsoidHierarchy`).
  var ellipsoidHierarchy: BoundingVolumeHierarchy<Scalar>?
  var wideEllipsoidHierarchy: WideHierarchy<Scalar>?
  /// Shapes of kinds the engine does not specialise, in the world's units,
  /// each tested through its own `Hittable.intersect` after a check of its
  /// box (`testShapes`); empty for every scene of the readers' own kinds.
  var shapes: [WorldShape] = []
  var shapeBoxes: [BoundingBox?] = []
  /// The shapes before this index have a bound, and are searched through
  /// `shapeHierarchy` when there is one.
  var boundedShapeCount = 0
  var shapeHierarchy: BoundingVolumeHierarchy<Double>?
  /// The eye in the world, in Double: where the shapes' rays start.
  let shapeEye: Vector3<Double>
  /// Objects the scene's common scale cannot hold, each group compiled at
  /// its own (`LengthScale.layers`) and searched after this scene's own
  /// search (`Renderer.store`); empty for every ordinary scene.
  package internal(set) var layers: [CompiledScene] = []
  package let materials: [Material<Scalar>]
  /// `materials` without their texture paths, for shading.
  let surfaces: [Material<Scalar>.Surface]
  /// Per material, its texture; empty when no material has one or the
  /// render shades nothing.
  package let textures: [Texture?]
  package let lights: [Light<Scalar>]
  package let ambient: RGB<Scalar>
  package let background: RGB<Scalar>
  /// Threads that build the hierarchies, now or when the render asks
  /// (`buildTriangleHierarchy`): the same hierarchy for any count.
  let threads: Int

  package var sphereCount: Int { spheres.count }
  package var planeCount: Int { planes.count }
  package var usesHierarchy: Bool { hierarchy != nil }
  package var usesTriangleHierarchy: Bool { triangleHierarchy != nil }

  /// - Parameters:
  ///   - hierarchyThreshold: the sphere count from which a BVH is built
  ///     (see `BoundingVolumeHierarchy.defaultThreshold`); below it,
  ///     spheres are culled per tile.
  ///   - projectionThreshold: the sphere count from which spheres are left
  ///     in scene order for `ScreenTiles`, with neither a BVH nor culling
  ///     data (supersampled renders widen the tiles' boxes by the filter's
  ///     reach).
  ///   - triangleProjectionThreshold: the count of triangles from which
  ///     they are left in order for `ScreenTiles` rather than given a
  ///     hierarchy; projection is declined, and the hierarchy built, when
  ///     the render finds them too many on screen.
  ///   - textures: per material, the texture a shaded render maps onto
  ///     triangles with texture coordinates (see `TextureLoader`); empty
  ///     for untextured scenes and for renders without a shaded image.
  ///   - threads: the render's, for building hierarchies.
  package init(
    _ scene: Scene, kernel: Kernel.Type = Kernel.self,
    textures: [Texture?] = [],
    hierarchyThreshold: Int = BoundingVolumeHierarchy<Scalar>.defaultThreshold,
    projectionThreshold: Int = .max, triangleProjectionThreshold: Int = .max,
    threads: Int = Platform.availableCores
  ) {
    // Lengths scaled by 2^−k when the scene is beyond the precision's
    // comfortable range (`LengthScale`); k = 0, nothing scaled, otherwise.
    // Objects the common scale cannot hold are traced at their own, each
    // group a scene of its own (`layers`).
    let split = LengthScale.layers(
      scene.root.flattened(threads: threads), eye: scene.camera.center,
      as: Scalar.self,
      threads: threads)
    self.init(
      scene, split.main, exponent: split.exponent, textures: textures,
      hierarchyThreshold: hierarchyThreshold,
      projectionThreshold: projectionThreshold,
      triangleProjectionThreshold: triangleProjectionThreshold,
      threads: threads)
    layers = split.others.map {
      CompiledScene(
        scene, $0.primitives, exponent: $0.exponent, textures: textures,
        hierarchyThreshold: hierarchyThreshold, projectionThreshold: .max,
        triangleProjectionThreshold: .max, threads: threads)
    }
  }

  /// The scene's `unscaled` primitives compiled at the scale 2^−`exponent`.
  private init(
    _ scene: Scene, _ unscaled: consuming Primitives<Double>, exponent: Int,
    textures: [Texture?], hierarchyThreshold: Int, projectionThreshold: Int,
    triangleProjectionThreshold: Int, threads: Int
  ) {
    self.threads = threads
    camera = PerspectiveCamera(scene.camera)
    eye = Vector3(scene.camera.center)
    shapeEye = scene.camera.center
    lengthScale = Scalar(LengthScale.factor(exponent))
    // Scaled by 2^−k, moved to the eye first where its coordinates would
    // leave the range (`LengthScale.frame`); as they are at k = 0.
    let (all, eyeDouble) = LengthScale.frame(
      unscaled, eye: scene.camera.center, exponent: exponent,
      as: Scalar.self)
    rayOrigin = Kernel.frameOrigin(eye: eyeDouble)
    let (sphereList, planeList) = (all.spheres, all.planes)
    spheres = Self.map(sphereList, threads: threads) {
      Kernel.makeSphere($0, eye: eyeDouble)
    }
    sphereMaterials = Self.map(sphereList, threads: threads) {
      Int32(truncatingIfNeeded: $0.materialIndex)
    }
    planes = planeList.map { Kernel.makePlane($0, eye: eyeDouble) }
    planeMaterials = planeList.map {
      Int32(truncatingIfNeeded: $0.materialIndex)
    }
    materials = scene.materials.map(Material.init)
    surfaces = materials.map(\.surface)
    self.textures = textures.contains { $0 != nil } ? textures : []
    lights = scene.lights.map(Light.init)
    ambient = Vector3(scene.ambient)
    background = Vector3(scene.background)
    if spheres.count >= projectionThreshold {
      projectsSpheres = true
    } else if spheres.count >= hierarchyThreshold {
      buildSphereHierarchy()
    } else {
      for record in spheres {
        let (center, radius) = cullBound(record)
        cullCenters.append(center)
        cullRadii.append(radius)
      }
    }
    // Triangles are never culled per tile: their hierarchy starts at the
    // flat loop's break-even however high the spheres' threshold is set.
    compileMeshesAndEllipsoids(
      consume all, eye: eyeDouble,
      hierarchyThreshold: Swift.min(
        hierarchyThreshold, BoundingVolumeHierarchy<Scalar>.defaultThreshold),
      projectionThreshold: triangleProjectionThreshold)
  }

  /// Builds the BVH over the spheres and stores them in its order: at
  /// compile time above the hierarchy threshold, or when `ScreenTiles`
  /// declines a scene whose spheres overlap too much on screen.
  mutating func buildSphereHierarchy() {
    let bvh = BoundingVolumeHierarchy(
      spheres: spheres, kernel: Kernel.self, rayOrigin: rayOrigin,
      threads: threads)
    let (unordered, unorderedMaterials) = (spheres, sphereMaterials)
    spheres = Self.map(bvh.order, threads: threads) { unordered[Int($0)] }
    sphereMaterials = Self.map(bvh.order, threads: threads) {
      unorderedMaterials[Int($0)]
    }
    hierarchy = bvh
    wideHierarchy = WideHierarchy(bvh, rayOrigin: rayOrigin)
    projectsSpheres = false
  }

  /// `transform` of each element in order, on up to `threads` threads
  /// from 2¹⁶ elements: the sphere records of the largest scenes, a large
  /// mesh's vertices.
  static func map<Element, Result>(
    _ elements: [Element], threads: Int, _ transform: (Element) -> Result
  ) -> [Result] {
    let parts = Parallel.parts(
      elements.count, threads: threads, from: 1 << 16, minimum: 1 << 15)
    return Array(unsafeUninitializedCapacity: elements.count) {
      results, initialized in
      Memory.adviseHugePages(UnsafeMutableRawBufferPointer(results))
      elements.withUnsafeBufferPointer { elements in
        Parallel.inParts(elements.count, parts) { _, range in
          for index in range {
            (results.baseAddress! + index).initialize(
              to: transform(elements[index]))
          }
        }
      }
      initialized = elements.count
    }
  }

  /// The triangles and ellipsoids of `all`, compiled for this kernel.
  private mutating func compileMeshesAndEllipsoids(
    _ all: consuming Primitives<Double>, eye: Vector3<Double>,
    hierarchyThreshold: Int, projectionThreshold: Int
  ) {
    let large = compileTriangles(all.triangles, eye: eye)
    // The model's triangles are not needed again: a transformed mesh's
    // placed copy is freed before the build.
    all.triangles = TriangleList()
    let ordinary = triangles.count
    appendLargeTriangles(large)
    if ordinary >= projectionThreshold {
      projectsTriangles = true
    } else if ordinary >= hierarchyThreshold {
      buildTriangleHierarchy()
    } else {
      buildLargeTriangleHierarchy()
    }
    for ellipsoid in all.transformedSpheres {
      ellipsoids.append(Kernel.makeEllipsoid(ellipsoid, eye: eye))
      ellipsoidMaterials.append(
        Int32(truncatingIfNeeded: ellipsoid.sphere.materialIndex))
    }
    buildEllipsoidHierarchy(all.transformedSpheres, eye: eye)
    placeShapes(all.shapes)
  }

  /// The sphere count from which single-sample renders project spheres
  /// onto screen tiles (`ScreenTiles`) rather than cull them per tile or
  /// build a hierarchy: every sphere scene in Double (on two threads,
  /// scenes of 1 to 200 spheres 10–18 % faster, the course scene 2–10 %),
  /// from 300 in Float, where projection measured 8–25 % slower below
  /// 300, for reasons not yet pinned down (docs/PERFORMANCE.md,
  /// "Thresholds").
  package static var projectionThreshold: Int {
    Scalar.significandBitCount > Float.significandBitCount ? 1 : 300
  }

  /// The same for supersampled renders: every scene with a sphere. Their
  /// tiles search and shade a tile's k-th samples together, and the course
  /// scene at 16 samples rendered 11 % faster so than culled per tile,
  /// random scenes of 1 to 200 spheres within ±4 % (docs/PERFORMANCE.md,
  /// "Thresholds").
  package static var supersampledProjectionThreshold: Int { 1 }

  package var triangleCount: Int { triangles.count }
  package var ellipsoidCount: Int { ellipsoids.count }

  /// What a camera ray hit first.
  package enum Nearest: Sendable {
    case sphere(Int)
    case plane(Int)
    /// Its barycentric weights are found again for the normal: carried
    /// here they made every hit record, sphere hits included, twice as big.
    case triangle(Int)
    case ellipsoid(Int)
    /// One of `shapes`.
    case shape(Int)
  }

  /// The unit normal of the hit `what` at `t`; for a triangle, from the
  /// barycentric `weights` of its test when given (`TriangleWeights`).
  func normal(
    of what: Nearest, _ ray: CameraRay<Scalar>, t: Scalar,
    weights: TriangleWeights<Scalar>? = nil
  ) -> Vector3<Scalar> {
    switch what {
    case .sphere(let index): Kernel.normal(spheres[index], ray, t: t)
    case .plane(let index): Kernel.normal(planes[index])
    case .triangle(let index):
      // Written as two lookups: a `switch` over the pair of optionals
      // made mesh renders 9 % slower.
      if let weights, let normals = vertexNormals(ofTriangle: index) {
        triangles[index].normal(weights: weights, normals: normals)
      } else {
        triangles[index].normal(
          of: ray, normals: vertexNormals(ofTriangle: index))
      }
    case .ellipsoid(let index):
      ellipsoids.withUnsafeBufferPointer {
        Kernel.normal($0[index], ray, t: t)
      }
    case .shape(let index):
      Vector3(shapeHit(index, ray)?.normal ?? .zero)
    }
  }

  /// The index into `materials` of the object hit.
  @inline(__always)
  func materialIndex(
    of what: Nearest, _ ray: CameraRay<Scalar>? = nil
  ) -> Int {
    let index: Int32
    switch what {
    case .sphere(let sphere): index = sphereMaterials[sphere]
    case .plane(let plane): index = planeMaterials[plane]
    case .triangle(let triangle): index = triangleSources.material(triangle)
    case .ellipsoid(let ellipsoid): index = ellipsoidMaterials[ellipsoid]
    case .shape(let shape):
      return ray.flatMap { shapeHit(shape, $0)?.materialIndex } ?? 0
    }
    return Int(index)
  }

  /// The colour of a hit at `point` with unit `normal`, by its material's
  /// `shade`: a textured material's diffuse colour is the texel at the
  /// hit's texture coordinates on triangles that have them; every other
  /// object keeps the material's own colour.
  ///
  /// Shaded from `surfaces`: a `Material` copied out of `materials` (its
  /// texture path is a string) went through the generic value witnesses
  /// and took a tenth of a supersampled render.
  @inline(__always)
  func shade(
    _ what: Nearest, _ ray: CameraRay<Scalar>, point: Vector3<Scalar>,
    normal: Vector3<Scalar>, attenuate: Bool
  ) -> RGB<Scalar> {
    let index = materialIndex(of: what, ray)
    if !textures.isEmpty, case .shape(let shape) = what,
      let texture = textures[index],
      let coordinate = shapeHit(shape, ray)?.textureCoordinate
    {
      var material = surfaces[index]
      material.diffuse = texture.color(
        at: TextureCoordinate<Scalar>(coordinate))
      return material.shade(
        point: point, normal: normal, viewDirection: ray.direction,
        ambient: ambient, lights: lights, attenuate: attenuate,
        power: specularPower)
    }
    if !textures.isEmpty, case .triangle(let triangle) = what,
      let texture = textures[index],
      let coordinates = triangleTextureCoordinates[triangle],
      let weights = triangles[triangle].barycentrics(of: ray)
    {
      var material = surfaces[index]
      material.diffuse = texture.color(
        at: coordinates.at(u: weights.u, v: weights.v, w: weights.w))
      return material.shade(
        point: point, normal: normal, viewDirection: ray.direction,
        ambient: ambient, lights: lights, attenuate: attenuate,
        power: specularPower)
    }
    return surfaces[index].shade(
      point: point, normal: normal, viewDirection: ray.direction,
      ambient: ambient, lights: lights, attenuate: attenuate,
      power: specularPower)
  }
}
