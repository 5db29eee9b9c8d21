import Geometry
import SceneDescription

/// The course's ray caster, as the slides give it: for every pixel a ray
/// from the camera; for every object of the scene the hit protocol
/// (`Hittable.intersect`); the closest t; shade.
///
/// It computes in Double with the scene's own lengths. Scenes of extreme
/// range (specks 10⁸ radii away, planets seen from one unit above) are the
/// other engine's job (docs/ENGINES.md).
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
    let width = settings.width
    // Each thread stores its rows' pixels in place.
    return RenderBuffers.written(
      width: width, height: settings.height, outputs: settings.outputs,
      threads: settings.threads, progress: progress
    ) { rows, pixels in
      for row in rows {
        for column in 0..<width {
          let pixel = row * width + column
          if settings.supersamplesAll {  // every output the samples' mean
            pixels.store(view.supersampled(column: column, row: row), at: pixel)
            continue
          }
          // The ray through the pixel's centre, and what it hits first.
          let ray = view.ray(column: column, row: row)
          let hit = view.world.intersect(ray, after: 0, before: .infinity)
          let color =
            !settings.outputs.contains(.shaded)
            ? .zero
            : settings.supersamples
              ? view.supersampled(column: column, row: row).color
              : view.color(ray, hit)
          // Depth and normal: the hit's t and normal, ∞ and zero on a miss.
          pixels.store(
            (hit?.t ?? .infinity, hit?.normal ?? .zero, color), at: pixel)
        }
      }
    }
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
