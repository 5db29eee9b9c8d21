/// The course's ray caster, exactly as the slides give it: for every pixel
/// a ray from the camera; for every object in the scene's group, the hit
/// protocol (`Intersectable.intersect`); the closest t; shade.
///
/// It renders the scene's model as read (`Scene.root`, in Double), its
/// transforms' objects placed in the world once (`Group.placed`), calling
/// `Sphere`, `Plane`, `Triangle` and `Group` for every ray, so a change to
/// any of them changes what it draws. The fast engine
/// (`Renderer`) gives the same images bit for bit from the same functions,
/// with the search structures of `Render/Search/` instead of the loop over
/// every object (tested on every project scene and the stiff suite).
/// Where two surfaces tie at exactly the same t, the course engine keeps
/// the first in the file, the fast engine the first by kind (spheres,
/// planes, triangles, ellipsoids); no scene of the project has such a tie.
///
/// A scene beyond Double's comfortable range is traced with its lengths
/// scaled by a power of two, exactly as the fast engine traces it
/// (`LengthScale`): the world's t is the traced t times `lengthScale`.
///
/// It computes in Double, the precision of the scene as read: a Float
/// render's records hold Double values rounded once, which no Float model
/// can hold (see docs/ENGINES.md).
public enum CourseEngine {
  /// Renders `scene` into the buffers `settings.outputs` asks for, rows
  /// spread over `settings.threads` (the image does not depend on them).
  ///
  /// - Precondition: `settings.precision == .double`.
  /// - Parameter textures: per material, its texture (see `TextureLoader`);
  ///   empty when nothing is textured or nothing is shaded.
  public static func render(
    _ scene: Scene, textures: [Texture?] = [], settings: RenderSettings,
    progress: (@Sendable (Int) -> Void)? = nil
  ) -> RenderBuffers<Double> {
    precondition(settings.precision == .double, "the course engine is Double")
    let (width, height) = (settings.width, settings.height)
    let pixels = Pixels(count: width * height, outputs: settings.outputs)
    let view = View(scene, textures: textures, settings: settings)
    Renderer.forEachRowBatch(
      rows: height, threads: settings.threads, progress: progress
    ) { rows in
      for row in rows {
        for column in 0..<width {
          view.render(column: column, row: row, into: pixels)
        }
      }
    }
    return pixels.buffers(width: width, height: height)
  }

  /// What every pixel needs: the camera, the scene and the settings.
  private struct View: Sendable {
    let camera: PerspectiveCamera<Double>
    let scene: Scene
    /// The scene's group with its transforms applied, its lengths scaled
    /// by 1 / `lengthScale`.
    let world: Group<Double>
    /// The eye, scaled as `world` is: where rays start.
    let origin: Vector3<Double>
    /// 2^k, 1 for every scene within Double's comfortable range.
    let lengthScale: Double
    let materials: [Material<Double>]
    let textures: [Texture?]
    let settings: RenderSettings
    let aspect: Double

    init(_ scene: Scene, textures: [Texture?], settings: RenderSettings) {
      camera = scene.camera.styled(settings.style)
      self.scene = scene
      let exponent = LengthScale.exponent(
        scene.root.flattened(), eye: scene.camera.center, as: Double.self)
      lengthScale = LengthScale.factor(exponent)
      if exponent == 0 {
        world = scene.root.placed()
        origin = camera.center
      } else {
        let factor = LengthScale.factor(-exponent)
        world = scene.root.placed().scaled(by: factor)
        origin = camera.center * factor
      }
      materials = scene.materials
      self.textures = textures
      self.settings = settings
      aspect = Double(settings.height) / Double(settings.width)
    }

    /// The ray from the eye through the pixel's centre (as the style
    /// places it).
    func ray(column: Int, row: Int) -> Ray<Double> {
      let style = settings.style
      let y: Double = style.screenY(row: row, height: settings.height)
      let x: Double = style.screenX(column: column, width: settings.width)
      let direction = camera.rayDirection(
        x: x, rowBase: camera.rowBase(y: y, aspect: aspect))
      return Ray(origin: origin, direction: direction)
    }

    /// The nearest hit of every object in the scene's group.
    func trace(_ ray: Ray<Double>) -> Hit<Double>? {
      world.intersect(
        ray, after: 0, before: .infinity, method: settings.method)
    }

    /// The colour seen along `ray`: the background on a miss, else the
    /// hit's material lit by every light (Phong). A textured material's
    /// diffuse colour is its texture's texel where the hit has texture
    /// coordinates.
    func color(_ ray: Ray<Double>, _ hit: Hit<Double>?) -> RGB<Double> {
      guard let hit else { return scene.background }
      var material = materials[hit.materialIndex]
      if !textures.isEmpty, let texture = textures[hit.materialIndex],
        let coordinate = hit.textureCoordinate
      {
        material.diffuse = texture.color(at: coordinate)
      }
      return material.shade(
        point: camera.center + ray.direction * (hit.t * lengthScale),
        normal: hit.normal,
        viewDirection: ray.direction, ambient: scene.ambient,
        lights: scene.lights, attenuate: settings.style == .mit)
    }

    func render(column: Int, row: Int, into pixels: Pixels) {
      let pixel = row * settings.width + column
      let ray = ray(column: column, row: row)
      let hit = trace(ray)
      if !pixels.depth.isEmpty {
        pixels.depth[pixel] = hit.map { $0.t * lengthScale } ?? .infinity
      }
      if !pixels.normals.isEmpty {
        pixels.normals[pixel] = hit?.normal ?? .zero
      }
      guard !pixels.color.isEmpty else { return }
      guard settings.samples > 1 else {
        pixels.color[pixel] = color(ray, hit)
        return
      }
      var sum = RGB<Double>.zero
      var samples = PixelSamples(
        column: column, row: row, camera: camera, settings: settings)
      while let direction = samples.next() {
        let sample = Ray(origin: origin, direction: direction)
        sum += color(sample, trace(sample))
      }
      pixels.color[pixel] = sum / Double(samples.count)
    }
  }

  /// The requested buffers, written by one thread per pixel.
  private final class Pixels: @unchecked Sendable {
    let depth: UnsafeMutableBufferPointer<Double>
    let normals: UnsafeMutableBufferPointer<Vector3<Double>>
    let color: UnsafeMutableBufferPointer<RGB<Double>>

    init(count: Int, outputs: RenderOutputs) {
      func buffer<T>(_ wanted: Bool, _ zero: T) -> UnsafeMutableBufferPointer<T>
      {
        let buffer = UnsafeMutableBufferPointer<T>.allocate(
          capacity: wanted ? count : 0)
        buffer.initialize(repeating: zero)
        return buffer
      }
      depth = buffer(outputs.contains(.depth), 0)
      normals = buffer(outputs.contains(.normals), .zero)
      color = buffer(outputs.contains(.shaded), .zero)
    }

    deinit {
      depth.deallocate()
      normals.deallocate()
      color.deallocate()
    }

    func buffers(width: Int, height: Int) -> RenderBuffers<Double> {
      RenderBuffers(
        width: width, height: height, depth: Array(depth),
        normals: Array(normals), color: Array(color))
    }
  }
}
