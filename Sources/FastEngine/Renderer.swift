import Dispatch
import Geometry
import SceneDescription
import PlatformSupport

/// The per-pixel loop: one camera ray per pixel, nearest hit, then only the
/// quantities the requested outputs need.
package enum Renderer {
  /// Renders `scene` into the buffers `settings.outputs` asks for.
  ///
  /// Rows are handed out to `settings.threads` workers in small batches; every
  /// pixel is computed by the same code whatever the thread count, so the
  /// result is identical bit for bit.
  package static func render<Kernel: IntersectionKernel>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    progress: (@Sendable (Int) -> Void)? = nil
  ) -> RenderBuffers<Kernel.Scalar> {
    renderReportingSearch(scene, settings: settings, progress: progress).buffers
  }

  /// How a render found each pixel's nearest sphere.
  package enum SphereSearch: Sendable, Equatable, CustomStringConvertible {
    case everySphere, culledPerTile, hierarchy, screenTiles

    /// In words, for a render's report.
    package var description: String {
      switch self {
      case .everySphere: "testing each"
      case .culledPerTile: "culling per tile"
      case .hierarchy: "BVH"
      case .screenTiles: "screen tiles"
      }
    }
  }

  /// How a render found each pixel's nearest triangle.
  package enum TriangleSearch: Sendable, Equatable, CustomStringConvertible {
    case everyTriangle, hierarchy, screenTiles

    /// In words, for a render's report.
    package var description: String {
      switch self {
      case .everyTriangle: "testing each"
      case .hierarchy: "BVH"
      case .screenTiles: "screen tiles"
      }
    }
  }

  /// `render`, and how it searched the spheres and triangles: a scene
  /// compiled for projection is projected onto screen tiles, or given its
  /// hierarchies when `ScreenTiles` declines it.
  ///
  /// - Parameter cache: where the scene's earlier renders left their
  ///   tiles and hierarchies (`SearchCache`); without it both are built
  ///   for this render alone.
  /// - Parameter recycling: an earlier render's buffers of the same size
  ///   and outputs, written over instead of allocating new ones (repeated
  ///   renders, `RenderSettings.repeats`): memory already faulted in.
  package static func renderReportingSearch<Kernel: IntersectionKernel>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    overlapLimit: Int = ScreenTiles<Kernel>.overlapLimit,
    cache: SearchCache<Kernel>? = nil,
    progress: (@Sendable (Int) -> Void)? = nil,
    recycling: consuming RenderBuffers<Kernel.Scalar>? = nil
  ) -> (
    buffers: RenderBuffers<Kernel.Scalar>, search: SphereSearch,
    triangleSearch: TriangleSearch
  ) {
    let (scene, tiles) =
      cache?.search(scene, settings: settings, overlapLimit: overlapLimit)
      ?? search(scene, settings: settings, overlapLimit: overlapLimit)
    let buffers = render(
      scene, settings: settings, rays: Kernel.Scalar.self, tiles: tiles,
      progress: progress, recycling: consume recycling)
    let search: SphereSearch =
      tiles != nil
      ? .screenTiles
      : scene.usesHierarchy
        ? .hierarchy
        : scene.cullsPerTile ? .culledPerTile : .everySphere
    let triangleSearch: TriangleSearch =
      scene.projectsTriangles
      ? .screenTiles
      : scene.usesTriangleHierarchy ? .hierarchy : .everyTriangle
    return (buffers, search, triangleSearch)
  }

  /// The scene to render and its tiles: the tiles of a scene compiled for
  /// projection, or, where there are none, the scene with its hierarchies.
  static func search<Kernel: IntersectionKernel>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings, overlapLimit: Int
  ) -> (scene: CompiledScene<Kernel>, tiles: ScreenTiles<Kernel>?) {
    if let tiles = tiles(scene, settings: settings, overlapLimit: overlapLimit)
    {
      return (scene, tiles)
    }
    return (hierarchical(scene), nil)
  }

  /// The screen tiles of a scene compiled for projection; nil when it
  /// projects nothing or `ScreenTiles` declines.
  static func tiles<Kernel: IntersectionKernel>(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings, overlapLimit: Int
  ) -> ScreenTiles<Kernel>? {
    guard scene.projectsSpheres || scene.projectsTriangles else { return nil }
    let camera = settings.camera(scene.camera, as: Kernel.Scalar.self)
    return ScreenTiles(
      scene, camera: camera, settings: settings, overlapLimit: overlapLimit)
  }

  /// `scene` searched by hierarchies where it would have projected: they
  /// depend on the scene alone, not on the view.
  static func hierarchical<Kernel: IntersectionKernel>(
    _ scene: CompiledScene<Kernel>
  ) -> CompiledScene<Kernel> {
    var scene = scene
    if scene.projectsSpheres { scene.buildSphereHierarchy() }
    if scene.projectsTriangles { scene.buildTriangleHierarchy() }
    return scene
  }

  /// Renders with camera rays generated in precision `RayPrecision` and then
  /// converted exactly to the kernel's wider type: the reference path, which
  /// intersects the very rays a Float or Double render traced, in Float80.
  package static func render<
    Kernel: IntersectionKernel, RayPrecision: RayScalar
  >(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    rays: RayPrecision.Type, progress: (@Sendable (Int) -> Void)? = nil
  ) -> RenderBuffers<Kernel.Scalar> {
    render(
      scene, settings: settings, rays: rays, tiles: nil, progress: progress,
      recycling: nil)
  }

  /// `tiles`, when given, must come from this scene, camera and settings;
  /// `recycling`'s arrays are reused where their sizes are the ones needed.
  private static func render<
    Kernel: IntersectionKernel, RayPrecision: RayScalar
  >(
    _ scene: CompiledScene<Kernel>, settings: RenderSettings,
    rays: RayPrecision.Type, tiles: ScreenTiles<Kernel>?,
    progress: (@Sendable (Int) -> Void)?,
    recycling: consuming RenderBuffers<Kernel.Scalar>?
  ) -> RenderBuffers<Kernel.Scalar> {
    typealias S = Kernel.Scalar
    let width = settings.width
    let height = settings.height
    let count = width * height
    let outputs = settings.outputs
    let camera = settings.camera(scene.camera, as: RayPrecision.self)
    // Left uninitialised: every pixel of every requested buffer is written
    // exactly once below, so zeroing them first would only cost a pass
    // over memory on one thread.
    // Outputs written only as 8-bit images are stored as their pixels.
    func counts(_ output: RenderOutputs) -> (values: Int, bytes: Int) {
      guard outputs.contains(output) else { return (0, 0) }
      return settings.quantizedOutputs.contains(output)
        ? (0, 3 * count) : (count, 0)
    }
    // The recycled arrays are taken out of their buffers, so that each is
    // referenced once and written in place.
    var old = (consume recycling) ?? RenderBuffers(width: 0, height: 0)
    var normals = old.normals
    var color = old.color
    var normalBytes = old.normalBytes
    var colorBytes = old.colorBytes
    var depth = old.depth
    old = RenderBuffers(width: 0, height: 0)
    fill(&depth, count: outputs.contains(.depth) ? count : 0) {
      depth in
      fill(&normals, count: counts(.normals).values) { normals in
        fill(&color, count: counts(.shaded).values) { color in
          fill(&normalBytes, count: counts(.normals).bytes) { normalBytes in
            fill(&colorBytes, count: counts(.shaded).bytes) { colorBytes in
              let targets = Targets(
                depth: depth, normals: normals, color: color,
                normalBytes: normalBytes, colorBytes: colorBytes,
                quantization: settings.quantization)
              // Screen x per column, once per render rather than a division
              // per pixel.
              let screen = settings.screen
              let columns = (0..<width).map { column -> RayPrecision in
                screen.x(column: column)
              }
              columns.withUnsafeBufferPointer { buffer in
                let columns = Shared(buffer)
                forEachRowBatch(
                  rows: height, threads: settings.threads, progress: progress
                ) { rows in
                  renderRows(
                    rows, columns.value, scene, camera, settings, tiles, targets
                  )
                }
              }
            }
          }
        }
      }
    }
    var buffers = RenderBuffers(
      width: width, height: height, depth: depth, normals: normals, color: color
    )
    buffers.normalBytes = normalBytes
    buffers.colorBytes = colorBytes
    return buffers
  }

  /// Makes `array` `count` elements that `initialize` must write, every
  /// one: the array's own storage when it has that many (a recycled
  /// buffer; the elements are plain values, written over), else a new,
  /// uninitialised one.
  static func fill<T>(
    _ array: inout [T], count: Int,
    _ initialize: (UnsafeMutableBufferPointer<T>) -> Void
  ) {
    guard array.count == count else {
      array = []
      array = Array(unsafeUninitializedCapacity: count) {
        buffer, initializedCount in
        Memory.adviseHugePages(UnsafeMutableRawBufferPointer(buffer))
        initialize(buffer)
        initializedCount = count
      }
      return
    }
    array.withUnsafeMutableBufferPointer { initialize($0) }
  }

  /// Disjoint rows of these buffers are written by different threads.
  /// Normals and colours go to their values or, for outputs only written
  /// as 8-bit images, to the style's pixels.
  struct Targets<S: RayScalar>: @unchecked Sendable {
    let depth: UnsafeMutableBufferPointer<S>
    let normals: UnsafeMutableBufferPointer<Vector3<S>>
    let color: UnsafeMutableBufferPointer<RGB<S>>
    let normalBytes: UnsafeMutableBufferPointer<UInt8>
    let colorBytes: UnsafeMutableBufferPointer<UInt8>
    let quantization: Quantization

    var wantsDepth: Bool { depth.count > 0 }
    var wantsNormals: Bool { normals.count > 0 || normalBytes.count > 0 }
    var wantsColor: Bool { color.count > 0 || colorBytes.count > 0 }

    @inline(__always)
    func setNormal(_ normal: Vector3<S>, at pixel: Int) {
      if normals.count > 0 {
        normals[pixel] = normal
      } else {
        Self.store(
          quantization.pixel(normal: normal), at: pixel, in: normalBytes)
      }
    }

    @inline(__always)
    func setColor(_ value: RGB<S>, at pixel: Int) {
      if color.count > 0 {
        color[pixel] = value
      } else {
        Self.store(quantization.pixel(value), at: pixel, in: colorBytes)
      }
    }

    @inline(__always)
    private static func store(
      _ value: (UInt8, UInt8, UInt8), at pixel: Int,
      in bytes: UnsafeMutableBufferPointer<UInt8>
    ) {
      bytes[3 * pixel] = value.0
      bytes[3 * pixel + 1] = value.1
      bytes[3 * pixel + 2] = value.2
    }
  }
}
