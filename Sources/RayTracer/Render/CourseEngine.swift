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
/// Objects that scale cannot hold are traced at their own, as the fast
/// engine traces them (`LengthScale.layers`): each layer's nearest hit is
/// compared in the world's units, the scene's own first.
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
    /// The scene's group with its transforms applied, then any objects
    /// traced at their own scale (`LengthScale.layers`), each with its
    /// lengths scaled by 1 / its `lengthScale`.
    let layers: [Layer]
    let materials: [Material<Double>]
    let textures: [Texture?]
    let settings: RenderSettings
    let aspect: Double

    /// Objects traced at one scale.
    struct Layer: Sendable {
      let world: Group<Double>
      /// The eye, scaled as `world` is: where rays start.
      let origin: Vector3<Double>
      /// 2^k, 1 for every scene within Double's comfortable range.
      let lengthScale: Double

      init(_ world: Group<Double>, eye: Vector3<Double>, exponent: Int) {
        let factor = LengthScale.factor(-exponent)
        self.world = exponent == 0 ? world : world.scaled(by: factor)
        origin = exponent == 0 ? eye : eye * factor
        lengthScale = LengthScale.factor(exponent)
      }
    }

    init(_ scene: Scene, textures: [Texture?], settings: RenderSettings) {
      camera = scene.camera.styled(settings.style)
      self.scene = scene
      let eye = camera.center
      let split = LengthScale.layers(
        scene.root.flattened(), eye: scene.camera.center, as: Double.self)
      if split.others.isEmpty {
        layers = [
          Layer(scene.root.placed(), eye: eye, exponent: split.exponent)
        ]
      } else {
        layers =
          [Layer(Group(split.main), eye: eye, exponent: split.exponent)]
          + split.others.map {
            Layer(Group($0.primitives), eye: eye, exponent: $0.exponent)
          }
      }
      materials = scene.materials
      self.textures = textures
      self.settings = settings
      aspect = Double(settings.height) / Double(settings.width)
    }

    /// The direction from the eye through the pixel's centre (as the
    /// style places it).
    func direction(column: Int, row: Int) -> Vector3<Double> {
      let style = settings.style
      let y: Double = style.screenY(row: row, height: settings.height)
      let x: Double = style.screenX(column: column, width: settings.width)
      return camera.rayDirection(
        x: x, rowBase: camera.rowBase(y: y, aspect: aspect))
    }

    /// The nearest hit of every object in the scene's group along
    /// `direction`, and the length scale its t is in.
    func trace(_ direction: Vector3<Double>) -> (
      hit: Hit<Double>, lengthScale: Double
    )? {
      var nearest: (hit: Hit<Double>, lengthScale: Double)?
      for layer in layers {
        let ray = Ray(origin: layer.origin, direction: direction)
        guard
          let hit = layer.world.intersect(
            ray, after: 0, before: .infinity, method: settings.method)
        else { continue }
        if let nearest,
          nearest.hit.t * nearest.lengthScale <= hit.t * layer.lengthScale
        {
          continue
        }
        nearest = (hit, layer.lengthScale)
      }
      return nearest
    }

    /// The colour seen along `direction`: the background on a miss, else
    /// the hit's material lit by every light (Phong). A textured
    /// material's diffuse colour is its texture's texel where the hit has
    /// texture coordinates.
    func color(
      _ direction: Vector3<Double>,
      _ found: (hit: Hit<Double>, lengthScale: Double)?
    ) -> RGB<Double> {
      guard let (hit, lengthScale) = found else { return scene.background }
      var material = materials[hit.materialIndex]
      if !textures.isEmpty, let texture = textures[hit.materialIndex],
        let coordinate = hit.textureCoordinate
      {
        material.diffuse = texture.color(at: coordinate)
      }
      return material.shade(
        point: camera.center + direction * (hit.t * lengthScale),
        normal: hit.normal,
        viewDirection: direction, ambient: scene.ambient,
        lights: scene.lights, attenuate: settings.style == .mit)
    }

    func render(column: Int, row: Int, into pixels: Pixels) {
      let pixel = row * settings.width + column
      let direction = direction(column: column, row: row)
      let found = trace(direction)
      if !pixels.depth.isEmpty {
        pixels.depth[pixel] =
          found.map { $0.hit.t * $0.lengthScale } ?? .infinity
      }
      if !pixels.normals.isEmpty {
        pixels.normals[pixel] = found?.hit.normal ?? .zero
      }
      guard !pixels.color.isEmpty else { return }
      guard settings.samples > 1 else {
        pixels.color[pixel] = color(direction, found)
        return
      }
      var sum = RGB<Double>.zero
      var samples = PixelSamples(
        column: column, row: row, camera: camera, settings: settings)
      while let sample = samples.next() {
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
