import Geometry
import SceneDescription

/// Reads the course's scene format:
///
///     PerspectiveCamera { center x y z  direction x y z  up x y z  angle deg }
///     Lights { numLights n  PointLight { position … color … [falloff f] }
///              DirectionalLight { direction … color … } }
///     Background { color r g b  ambientLight r g b }
///     Materials { numMaterials n  Material { diffuseColor … [specularColor …]
///                 [shininess s] [texture PATH] }  PhongMaterial { … } }
///     Group { numObjects n  MaterialIndex i  Sphere { center … radius r }
///             Plane { normal … offset d }  Triangle { vertex0 … }
///             TriangleMesh { obj_file PATH }  Transform { … }  Group { … } }
///
/// Paths are relative to the scene file's folder. Meshes are read as
/// `options` says (see `MeshLoader`).
///
/// Only the camera and the group are required. Fields inside a block may come
/// in any order, each once. Every problem is a `SceneError` at the offending
/// token; nothing traps, whatever the input.
package struct SceneParser {
  /// Deeper nesting than this is refused rather than risking the stack.
  package static let maximumGroupDepth = 200

  /// Longer words are refused at their position: no keyword or number
  /// needs a thousandth of it, and quoting a 50 MB word in a message, or
  /// comparing it with every keyword for a suggestion, would cost more than
  /// the whole file.
  package static let maximumWordLength = 4096

  /// The shortest object, `Group{numObjects 0}`: a file of n bytes holds at
  /// most n / 19 objects, however they nest.
  static let minimumObjectLength = 19

  /// Blocks of the course's later assignments: named in the error, with
  /// what raytrace has in their place, so a user knows the scene is valid
  /// but beyond this renderer.
  static let unsupportedBlocks: [String: String] = {
    var blocks = ["OrthographicCamera": "one camera is PerspectiveCamera"]
    let materials = [
      "texture", "bump", "CheckerBoard", "Checkerboard", "Noise",
      "PerlinNoise", "Marble", "Wood",
    ]
    for name in materials {
      blocks[name] =
        "materials are Material and PhongMaterial, "
        + "with an image as an optional texture"
    }
    for name in ["Box", "Cylinder", "Cone"] {
      blocks[name] =
        "shapes are Sphere, Plane, Triangle and TriangleMesh, "
        + "in Groups and Transforms (a shape of your own: "
        + "docs/ADDING-A-SHAPE.md)"
    }
    return blocks
  }()

  var tokenizer: SceneTokenizer
  let file: String
  let options: SceneOptions
  /// The materials, once their block is read: a mesh reads `a/b` faces by
  /// whether its material has a texture.
  var parsedMaterials: [Material<Double>]?
  /// Every mesh file read, for `Scene.meshFiles`.
  var meshFiles: [String] = []
  /// Each mesh file read once, however often the scene names it.
  let meshCache = MeshLoader.Cache()
  /// Meshes without texture coordinates, checked against their material
  /// when the scene is read: a textured material needs them.
  var meshesWithoutTextureCoordinates:
    [(material: Int, token: SceneToken, path: String)] = []
  var pendingMaterialChecks: [(index: Int, token: SceneToken)] = []
  /// Objects reserved so far for the counts groups declare. Reservations
  /// draw on what the file could hold, so a `numObjects` that lies, at any
  /// depth, allocates no more than the file could fill.
  var reservedObjects = 0
  let objectBudget: Int
  /// Transforms open at the current position: only the outermost one checks
  /// the geometry it produces, so each primitive is moved and checked once.
  var openTransforms = 0
  /// The material a `SphereRun` gives the spheres it reads.
  var currentMaterial = 0
  var splicedObjects = 0
  /// Off only in tests, which compare the sphere reading of
  /// `SceneTokenizer.plainSphere` with the token by token one.
  var readsPlainSpheres = true
  var concurrentFrom = (
    groupSize: SceneParser.concurrentGroupSize,
    bytes: SceneParser.concurrentBytes
  )

  /// Parses `text`; `file` names it in messages.
  package static func parse(
    _ text: String, file: String, options: SceneOptions = .init(style: .course)
  ) throws(SceneError) -> Scene {
    try parse(bytes: Array(text.utf8), file: file, options: options)
  }

  /// Parses raw bytes, which need not be valid UTF-8: what a file on disk
  /// holds, and what the fuzzer (Fuzz/FuzzSceneParser.swift) feeds.
  static func parse(
    bytes: [UInt8], file: String, options: SceneOptions = .init(style: .course)
  ) throws(SceneError) -> Scene {
    var parser = SceneParser(
      bytes: SceneBytes(bytes), file: file, options: options)
    return try parser.parseScene()
  }

  /// As `parse(bytes:file:)`, reading groups of at least `groupSize`
  /// objects on two threads where at least `bytes` are left: for tests,
  /// which split small files. `spliced` counts the objects the second
  /// thread read.
  static func parse(
    bytes: [UInt8], file: String, concurrentFrom: (groupSize: Int, bytes: Int),
    spliced: inout Int
  ) throws(SceneError) -> Scene {
    var parser = SceneParser(bytes: bytes, file: file)
    parser.concurrentFrom = concurrentFrom
    defer { spliced = parser.splicedObjects }
    return try parser.parseScene()
  }

  /// Reads and parses the text scene file at `path` (see `SceneReader`
  /// for either format).
  package static func parse(
    contentsOf path: String, options: SceneOptions = .init(style: .course)
  ) throws(SceneError) -> Scene {
    let bytes: SceneBytes
    do {
      bytes = try SceneBytes.contentsOf(path, threads: options.threads)
    } catch {
      throw SceneError(file: path, line: 0, column: 0, message: error.reason)
    }
    var parser = SceneParser(bytes: bytes, file: path, options: options)
    return try parser.parseScene()
  }

  init(
    bytes: [UInt8], file: String, options: SceneOptions = .init(style: .course)
  ) {
    self.init(bytes: SceneBytes(bytes), file: file, options: options)
  }

  init(bytes: SceneBytes, file: String, options: SceneOptions) {
    tokenizer = SceneTokenizer(bytes: bytes)
    self.file = file
    self.options = options
    objectBudget = bytes.buffer.count / Self.minimumObjectLength
  }

  // MARK: - Blocks

  mutating func parseScene() throws(SceneError) -> Scene {
    if let problem = options.shapeNameProblem() {
      throw SceneError(file: file, line: 0, column: 0, message: problem)
    }
    var camera: PerspectiveCamera<Double>?
    var lights: [Light<Double>]?
    var background: (color: RGB<Double>?, ambient: RGB<Double>?)?
    var materials: [Material<Double>]?
    var root: Group<Double>?
    var first: SceneToken?
    while true {
      let token = try next()
      if first == nil { first = token }
      switch token.kind {
      case .end:
        guard let camera else {
          throw error(at: first ?? token, "the scene has no PerspectiveCamera")
        }
        guard let root else {
          throw error(at: first ?? token, "the scene has no Group")
        }
        let materialList = materials ?? []
        let available = max(materialList.count, 1)
        for check in pendingMaterialChecks where check.index >= available {
          let count = materialList.count
          let available =
            count == 0
            ? "no materials (only the default, 0)"
            : "\(count) material\(count == 1 ? "" : "s") (0 to \(count - 1))"
          throw error(
            at: check.token,
            "MaterialIndex \(check.index) is out of range: the scene has "
              + available)
        }
        for mesh in meshesWithoutTextureCoordinates
        where materialList.indices.contains(mesh.material)
          && materialList[mesh.material].texturePath != nil
        {
          throw error(
            at: mesh.token,
            "material \(mesh.material) has a texture, but the mesh "
              + "'\(Self.escaped(mesh.path))' has no texture coordinates "
              + "(no face gives vt)")
        }
        var scene = Scene(
          camera: camera, lights: lights ?? [],
          background: background?.color ?? .zero,
          ambient: background?.ambient, materials: materialList, root: root)
        scene.meshFiles = meshFiles
        return scene
      case .open, .close:
        throw error(at: token, "expected a block name, found '\(text(token))'")
      case .word:
        let name = text(token)
        switch name {
        case "PerspectiveCamera":
          try refuseRepeat(camera != nil, token)
          camera = try parseCamera(token)
        case "Lights":
          try refuseRepeat(lights != nil, token)
          lights = try parseLights()
        case "Background":
          try refuseRepeat(background != nil, token)
          background = try parseBackground()
        case "Materials":
          try refuseRepeat(materials != nil, token)
          materials = try parseMaterials()
          parsedMaterials = materials
        case "Group":
          try refuseRepeat(root != nil, token)
          root = try parseGroup(depth: 1, material: 0)
        default:
          throw unexpected(
            token, expected: "a block name",
            choices: [
              "PerspectiveCamera", "Lights", "Background", "Materials", "Group",
            ])
        }
      }
    }
  }

  func refuseRepeat(_ seen: Bool, _ token: SceneToken)
    throws(SceneError)
  {
    if seen {
      throw error(at: token, "a second '\(text(token))' block; a scene has one")
    }
  }

  mutating func parseCamera(
    _ start: SceneToken
  ) throws(SceneError) -> PerspectiveCamera<Double> {
    var center: Vector3<Double>?
    var direction: (Vector3<Double>, SceneToken)?
    var up: (Vector3<Double>, SceneToken)?
    var angle: (Double, SceneToken)?
    let close = try parseFields(
      "PerspectiveCamera", ["center", "direction", "up", "angle"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "center": center = try parser.vector()
      case "direction":
        let token = parser.peekStart()
        direction = (try parser.vector(), token)
      case "up":
        let token = parser.peekStart()
        up = (try parser.vector(), token)
      default:
        let token = parser.peekStart()
        angle = (try parser.number(), token)
      }
    }
    guard let center, let direction, let up, let angle else {
      throw missing(
        "PerspectiveCamera",
        [
          ("center", center != nil), ("direction", direction != nil),
          ("up", up != nil), ("angle", angle != nil),
        ], close)
    }
    guard angle.0 > 0 && angle.0 < 180 else {
      throw error(
        at: angle.1,
        "the camera's angle must be between 0 and 180 degrees, found "
          + text(angle.1))
    }
    guard direction.0.maxMagnitude > 0 else {
      throw error(at: direction.1, "the camera's direction must not be zero")
    }
    guard
      let camera = PerspectiveCamera(
        center: center, direction: direction.0, up: up.0, angle: angle.0)
    else {
      throw error(
        at: up.1,
        "the camera's up vector must not be zero or parallel to its direction")
    }
    return camera
  }
}
