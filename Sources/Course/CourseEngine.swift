import Foundation
import Geometry
import SceneDescription

/// The course's ray caster, as the slides give it: for every pixel a ray
/// from the camera; for every object of the scene the hit protocol
/// (`Hittable.intersect`); the closest t; shade.
///
/// It computes in Double with the scene's own lengths. Scenes of extreme
/// range (specks 10⁸ radii away, planets seen from one unit above) are the
/// fast engine's job (`--engine fast`, docs/ENGINES.md).
public enum CourseEngine {
  /// Renders `scene` into the buffers `settings.outputs` asks for, rows
  /// spread over `settings.threads` (the image does not depend on them).
  ///
  /// - Parameter textures: per material, its texture; empty when nothing
  ///   is textured or nothing is shaded.
  public static func render(
    _ scene: Scene, textures: [Texture?] = [], settings: RenderSettings,
    progress: (@Sendable (Int) -> Void)? = nil
  ) -> RenderBuffers<Double> {
    let view = View(scene, textures: textures, settings: settings)
    let (width, height) = (settings.width, settings.height)
    let outputs = settings.outputs
    let image = Image(width: width, height: height, outputs: outputs)
    RowBatches.forEach(
      rows: height, threads: settings.threads, progress: progress
    ) { rows in
      for row in rows {
        var pixels = Image.Row()
        for column in 0..<width {
          if settings.supersamplesAll {  // every output the samples' mean
            pixels.append(view.supersampled(column: column, row: row), outputs)
            continue
          }
          // The ray through the pixel's centre, and what it hits first.
          let ray = view.ray(column: column, row: row)
          let hit = view.world.intersect(ray, after: 0, before: .infinity)
          if outputs.contains(.depth) {
            pixels.depth.append(hit?.t ?? .infinity)
          }
          if outputs.contains(.normals) {
            pixels.normals.append(hit?.normal ?? .zero)
          }
          if outputs.contains(.shaded) {
            pixels.color.append(
              settings.supersamples
                ? view.supersampled(column: column, row: row).color
                : view.color(ray, hit))
          }
        }
        image.store(pixels, at: row)
      }
    }
    return image.buffers()
  }
}

/// What every pixel needs: the camera, the course's objects, the lights and
/// materials.
struct View: Sendable {
  let scene: Scene
  let camera: PerspectiveCamera<Double>
  let world: Group
  let textures: [Texture?]
  let settings: RenderSettings

  init(_ scene: Scene, textures: [Texture?], settings: RenderSettings) {
    self.scene = scene
    camera = settings.camera(scene.camera)
    world = SceneObjects.group(scene.root)
    self.textures = textures
    self.settings = settings
  }

  /// The ray from the eye through the centre of pixel (column, row), where
  /// the image style puts it on the screen [−1, 1]² (docs/CONVENTIONS.md).
  func ray(column: Int, row: Int) -> Ray<Double> {
    // BEGIN SOLUTION week 1: camera and planes — the ray from the eye
    //   through the pixel's screen point (settings.screen), its direction
    //   x·u + (H/W)·y·v + D·w normalised (camera.rayDirection)
    let x: Double = settings.screen.x(column: column)
    let y: Double = settings.screen.y(row: row)
    let aspect = Double(settings.height) / Double(settings.width)
    return Ray(
      origin: camera.center,
      direction: camera.rayDirection(x: x, y: y, aspect: aspect))
    // END SOLUTION
  }

  /// The colour seen along `ray`: the background on a miss, else the hit's
  /// material lit by every light (Phong, `Material.Surface.shade`). A
  /// textured material's diffuse colour is the texel at the hit's texture
  /// coordinates, where the object has them.
  func color(_ ray: Ray<Double>, _ hit: Hit<Double>?) -> RGB<Double> {
    // BEGIN SOLUTION week 3: shading — the background on a miss, else
    //   the hit's material (a texture's texel as its diffuse colour) lit by
    //   the ambient light and every light (Material.Surface.shade)
    guard let hit else { return scene.background }
    // Its colours only (no file name: no string counted per pixel).
    var surface = scene.materials[hit.materialIndex].surface
    if !textures.isEmpty, let texture = textures[hit.materialIndex],
      let coordinate = hit.textureCoordinate
    {
      surface.diffuse = texture.color(at: coordinate)
    }
    return surface.shade(
      point: ray.point(at: hit.t), normal: hit.normal,
      viewDirection: ray.direction, ambient: scene.ambient,
      lights: scene.lights, attenuate: settings.attenuatesLights)
    // END SOLUTION
  }

  typealias Pixel = (depth: Double, normal: Vector3<Double>, color: RGB<Double>)

  /// The means of the pixel's jittered samples (`PixelSamples`): colour;
  /// depth over the samples that hit (∞ if none); normal, a miss as zero.
  func supersampled(column: Int, row: Int) -> Pixel {
    var samples = PixelSamples(
      column: column, row: row, camera: camera, settings: settings)
    var (sum, hits): (Pixel, Int) = ((0, .zero, .zero), 0)
    while let direction = samples.next() {
      let ray = Ray(origin: camera.center, direction: direction)
      let hit = world.intersect(ray, after: 0, before: .infinity)
      if settings.outputs.contains(.shaded) { sum.color += color(ray, hit) }
      guard let hit else { continue }
      (sum.depth, hits) = (sum.depth + hit.t, hits + 1)
      sum.normal += hit.normal
    }
    let count = Double(samples.count)
    sum.depth = hits > 0 ? sum.depth / Double(hits) : .infinity
    return (sum.depth, sum.normal / count, sum.color / count)
  }
}

/// The image being rendered, row by row: each row is computed on its own,
/// then stored under a lock, so threads never write the same memory.
private final class Image: @unchecked Sendable {
  struct Row {
    var depth: [Double] = []
    var normals: [Vector3<Double>] = []
    var color: [RGB<Double>] = []
    mutating func append(_ pixel: View.Pixel, _ outputs: RenderOutputs) {
      if outputs.contains(.depth) { depth.append(pixel.depth) }
      if outputs.contains(.normals) { normals.append(pixel.normal) }
      if outputs.contains(.shaded) { color.append(pixel.color) }
    }
  }

  private let lock = NSLock()
  private var image: RenderBuffers<Double>

  init(width: Int, height: Int, outputs: RenderOutputs) {
    func buffer<T>(_ output: RenderOutputs, _ zero: T) -> [T] {
      outputs.contains(output)
        ? Array(repeating: zero, count: width * height)
        : []
    }
    image = RenderBuffers(
      width: width, height: height, depth: buffer(.depth, 0),
      normals: buffer(.normals, .zero), color: buffer(.shaded, .zero))
  }

  func store(_ row: Row, at index: Int) {
    let pixels = index * image.width..<(index + 1) * image.width
    lock.lock()
    defer { lock.unlock() }
    func put<T>(_ values: [T], in buffer: inout [T]) {
      if !buffer.isEmpty { buffer.replaceSubrange(pixels, with: values) }
    }
    put(row.depth, in: &image.depth)
    put(row.normals, in: &image.normals)
    put(row.color, in: &image.color)
  }

  func buffers() -> RenderBuffers<Double> {
    lock.lock()
    defer { lock.unlock() }
    return image
  }
}
