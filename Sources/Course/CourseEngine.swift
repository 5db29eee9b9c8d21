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
                ? view.supersampledColor(column: column, row: row)
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

  /// The mean colour of the pixel's jittered samples (`PixelSamples`).
  func supersampledColor(column: Int, row: Int) -> RGB<Double> {
    var samples = PixelSamples(
      column: column, row: row, camera: camera, settings: settings)
    var sum = RGB<Double>.zero
    while let direction = samples.next() {
      let ray = Ray(origin: camera.center, direction: direction)
      sum += color(ray, world.intersect(ray, after: 0, before: .infinity))
    }
    return sum / Double(samples.count)
  }
}

/// The image being rendered, row by row: each row is computed on its own,
/// then stored under a lock, so threads never write the same memory.
private final class Image: @unchecked Sendable {
  struct Row {
    var depth: [Double] = []
    var normals: [Vector3<Double>] = []
    var color: [RGB<Double>] = []
  }

  private let width: Int
  private let height: Int
  private let lock = NSLock()
  private var depth: [Double]
  private var normals: [Vector3<Double>]
  private var color: [RGB<Double>]

  init(width: Int, height: Int, outputs: RenderOutputs) {
    self.width = width
    self.height = height
    let count = width * height
    depth = outputs.contains(.depth) ? Array(repeating: 0, count: count) : []
    normals =
      outputs.contains(.normals) ? Array(repeating: .zero, count: count) : []
    color =
      outputs.contains(.shaded) ? Array(repeating: .zero, count: count) : []
  }

  func store(_ row: Row, at index: Int) {
    let pixels = index * width..<(index + 1) * width
    lock.lock()
    defer { lock.unlock() }
    if !depth.isEmpty { depth.replaceSubrange(pixels, with: row.depth) }
    if !normals.isEmpty { normals.replaceSubrange(pixels, with: row.normals) }
    if !color.isEmpty { color.replaceSubrange(pixels, with: row.color) }
  }

  func buffers() -> RenderBuffers<Double> {
    lock.lock()
    defer { lock.unlock() }
    return RenderBuffers(
      width: width, height: height, depth: depth, normals: normals,
      color: color)
  }
}
