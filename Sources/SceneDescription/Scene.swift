import Geometry

/// A parsed scene, in Double: the file's values rounded once. Renders convert
/// it to their own precision when they compile it.
public struct Scene: Sendable {
  public var camera: PerspectiveCamera<Double>
  public var lights: [Light<Double>]
  public var background: RGB<Double>
  /// The ambient light; when the file gives none it is white for a scene
  /// without lights (so an unlit scene still shows its colours) and black
  /// otherwise.
  public var ambient: RGB<Double>
  /// Never empty: a scene without materials gets one matte white material.
  public var materials: [Material<Double>]
  public var root: Group<Double>
  /// The mesh files the scene read, as opened (its textures are named by
  /// the materials).
  public var meshFiles: [String] = []

  public init(
    camera: PerspectiveCamera<Double>, lights: [Light<Double>] = [],
    background: RGB<Double> = .zero, ambient: RGB<Double>? = nil,
    materials: [Material<Double>] = [], root: Group<Double>
  ) {
    self.camera = camera
    self.lights = lights
    self.background = background
    self.ambient = ambient ?? (lights.isEmpty ? Vector3(1, 1, 1) : .zero)
    self.materials = materials.isEmpty ? [.defaultWhite] : materials
    self.root = root
  }
}
