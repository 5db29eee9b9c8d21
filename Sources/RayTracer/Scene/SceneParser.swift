import Dispatch

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
public struct SceneParser {
  /// Deeper nesting than this is refused rather than risking the stack.
  public static let maximumGroupDepth = 200

  /// Longer words are refused at their position: no keyword or number
  /// needs a thousandth of it, and quoting a 50 MB word in a message, or
  /// comparing it with every keyword for a suggestion, would cost more than
  /// the whole file.
  public static let maximumWordLength = 4096

  /// The shortest object, `Group{numObjects 0}`: a file of n bytes holds at
  /// most n / 19 objects, however they nest.
  static let minimumObjectLength = 19

  /// Blocks of the course's later assignments: named in the error, so a user
  /// knows the scene is valid but beyond this renderer.
  static let unsupportedBlocks: Set<String> = [
    "OrthographicCamera", "texture", "bump", "CheckerBoard", "Noise", "Marble",
    "Wood",
    "PerlinNoise", "Checkerboard", "Box", "Cylinder", "Cone",
  ]

  private var tokenizer: SceneTokenizer
  private let file: String
  private let options: SceneOptions
  /// The materials, once their block is read: a mesh reads `a/b` faces by
  /// whether its material has a texture.
  private var parsedMaterials: [Material<Double>]?
  /// Meshes without texture coordinates, checked against their material
  /// when the scene is read: a textured material needs them.
  /// Every mesh file read, for `Scene.meshFiles`.
  private var meshFiles: [String] = []
  private var meshesWithoutTextureCoordinates:
    [(material: Int, token: SceneToken, path: String)] = []
  private var pendingMaterialChecks: [(index: Int, token: SceneToken)] = []
  /// Objects reserved so far for the counts groups declare. Reservations
  /// draw on what the file could hold, so a `numObjects` that lies, at any
  /// depth, allocates no more than the file could fill.
  private(set) var reservedObjects = 0
  private let objectBudget: Int
  /// Transforms open at the current position: only the outermost one checks
  /// the geometry it produces, so each primitive is moved and checked once.
  private var openTransforms = 0
  /// The material a `SphereRun` gives the spheres it reads.
  private var currentMaterial = 0
  private var splicedObjects = 0
  /// Off only in tests, which compare the sphere reading of
  /// `SceneTokenizer.plainSphere` with the token by token one.
  var readsPlainSpheres = true
  private var concurrentFrom = (
    groupSize: SceneParser.concurrentGroupSize,
    bytes: SceneParser.concurrentBytes
  )

  /// Parses `text`; `file` names it in messages.
  public static func parse(
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
  public static func parse(
    contentsOf path: String, options: SceneOptions = .init(style: .course)
  ) throws(SceneError) -> Scene {
    let bytes: SceneBytes
    do {
      bytes = try SceneBytes.contentsOf(path)
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
          throw error(
            at: check.token,
            "MaterialIndex \(check.index) is out of range: the scene has "
              + "\(materialList.isEmpty ? "no materials (only the default, 0)" : "\(materialList.count) material\(materialList.count == 1 ? "" : "s") (0 to \(materialList.count - 1))")"
          )
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

  private func refuseRepeat(_ seen: Bool, _ token: SceneToken)
    throws(SceneError)
  {
    if seen {
      throw error(at: token, "a second '\(text(token))' block; a scene has one")
    }
  }

  private mutating func parseCamera(
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
        "the camera's angle must be between 0 and 180 degrees, found \(text(angle.1))"
      )
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

  private mutating func parseLights() throws(SceneError) -> [Light<Double>] {
    try expect(.open, "'{' after Lights")
    let declared = try count("numLights", in: "Lights")
    var lights: [Light<Double>] = []
    while true {
      let token = try next()
      if token.kind == .close {
        try checkCount(
          lights.count, declared, "Lights", "numLights", "light", token)
        return lights
      }
      guard token.kind == .word else {
        throw unexpectedEnd(token, in: "Lights")
      }
      let name = text(token)
      if name == "PointLight" || name == "DirectionalLight" {
        if lights.count == declared.value {
          throw tooMany(declared, "Lights", "numLights", "light", token)
        }
        lights.append(
          name == "PointLight"
            ? try parsePointLight() : try parseDirectionalLight())
      } else {
        throw unexpected(
          token, expected: "a light",
          choices: ["PointLight", "DirectionalLight"])
      }
    }
  }

  private mutating func parsePointLight() throws(SceneError) -> Light<Double> {
    var position: Vector3<Double>?
    var color: RGB<Double>?
    var falloff: Double?
    let close = try parseFields(
      "PointLight", ["position", "color", "falloff"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "position": position = try parser.vector()
      case "color": color = try parser.color(field)
      default: falloff = try parser.positive(field)
      }
    }
    guard let position, let color else {
      throw missing(
        "PointLight", [("position", position != nil), ("color", color != nil)],
        close)
    }
    return .point(position: position, color: color, falloff: falloff)
  }

  private mutating func parseDirectionalLight() throws(SceneError) -> Light<
    Double
  > {
    var direction: Vector3<Double>?
    var color: RGB<Double>?
    let close = try parseFields(
      "DirectionalLight", ["direction", "color"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "direction": direction = try parser.nonZeroVector(field)
      default: color = try parser.color(field)
      }
    }
    guard let direction, let color else {
      throw missing(
        "DirectionalLight",
        [("direction", direction != nil), ("color", color != nil)],
        close)
    }
    return .directional(direction: direction.normalized(), color: color)
  }

  private mutating func parseBackground() throws(SceneError) -> (
    color: RGB<Double>?, ambient: RGB<Double>?
  ) {
    var color: RGB<Double>?
    var ambient: RGB<Double>?
    _ = try parseFields(
      "Background", ["color", "ambientLight", "cubeMap"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "color": color = try parser.color(field)
      case "ambientLight": ambient = try parser.color(field)
      default:
        // An environment map for reflected rays, which a ray caster never
        // traces: accepted so that the course's scenes load, and ignored
        // (misses show the background colour).
        let path = try parser.next()
        guard path.kind == .word else {
          throw parser.error(
            at: path, "expected the cube map's path after 'cubeMap'")
        }
      }
    }
    return (color, ambient)
  }

  private mutating func parseMaterials() throws(SceneError) -> [Material<
    Double
  >] {
    try expect(.open, "'{' after Materials")
    let declared = try count("numMaterials", in: "Materials")
    var materials: [Material<Double>] = []
    while true {
      let token = try next()
      if token.kind == .close {
        try checkCount(
          materials.count, declared, "Materials", "numMaterials", "material",
          token)
        return materials
      }
      guard token.kind == .word else {
        throw unexpectedEnd(token, in: "Materials")
      }
      let name = text(token)
      guard name == "Material" || name == "PhongMaterial" else {
        throw unexpected(
          token, expected: "a material", choices: ["Material", "PhongMaterial"])
      }
      if materials.count == declared.value {
        throw tooMany(declared, "Materials", "numMaterials", "material", token)
      }
      materials.append(try parseMaterial(name))
    }
  }

  private mutating func parseMaterial(_ name: String) throws(SceneError)
    -> Material<Double>
  {
    var diffuse: RGB<Double>?
    var specular: RGB<Double>?
    var shininess: Double?
    var texture: String?
    let close = try parseFields(
      name, ["diffuseColor", "specularColor", "shininess", "texture"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      switch field {
      case "diffuseColor": diffuse = try parser.color(field)
      case "specularColor": specular = try parser.color(field)
      case "texture": texture = parser.resolved(try parser.path(after: field).0)
      default: shininess = try parser.nonNegative(field)
      }
    }
    guard let diffuse else {
      throw missing(name, [("diffuseColor", false)], close)
    }
    return Material(
      diffuse: diffuse, specular: specular ?? .zero, shininess: shininess ?? 0,
      texturePath: texture)
  }

  /// A group's objects take the material set by the last `MaterialIndex`
  /// before them; a nested group starts with its parent's current material.
  private mutating func parseGroup(
    depth: Int, material inherited: Int
  ) throws(SceneError) -> Group<Double> {
    try expect(.open, "'{' after Group")
    let declared = try count("numObjects", in: "Group")
    var state = GroupState(
      declared: declared, depth: depth, material: inherited)
    let reserved = min(declared.value, objectBudget - reservedObjects)
    reservedObjects += reserved
    state.objects.reserveCapacityOnHugePages(reserved)
    var first: SceneToken?
    if let split = speculationPoint(declared: declared.value) {
      switch try parseObjectsAlongside(&state, from: split) {
      case .closed(let group): return group
      case .reached(let token): first = token
      case .spliced: first = nil
      }
    }
    guard case .closed(let group) = try parseObjects(&state, first: first)
    else {
      preconditionFailure("a group read without a limit ends at its '}'")
    }
    return group
  }

  /// A group being read: its objects so far and the current material.
  struct GroupState {
    let declared: (value: Int, token: SceneToken)
    let depth: Int
    var material: Int
    var objects: [SceneObject<Double>] = []
  }

  enum GroupProgress {
    case closed(Group<Double>)
    /// The first token at or past the limit, not yet looked at.
    case reached(SceneToken)
    /// Another parser's objects were added; go on from where it stopped.
    case spliced
  }

  /// Reads the group's objects, starting with `first` when given, up to
  /// its closing brace or the first token that starts at or past `limit`.
  private mutating func parseObjects(
    _ state: inout GroupState, first: SceneToken?, limit: Int = .max
  ) throws(SceneError) -> GroupProgress {
    var pending = first
    while true {
      let token: SceneToken
      if let given = pending {
        token = given
        pending = nil
      } else {
        token = try next()
        if token.start >= limit { return .reached(token) }
      }
      switch token.kind {
      case .close:
        try checkCount(
          state.objects.count, state.declared, "Group", "numObjects", "object",
          token)
        return .closed(Group(state.objects))
      case .end, .open:
        throw unexpectedEnd(token, in: "Group")
      case .word:
        break
      }
      // Spheres first, the objects of large scenes: the checks below, in
      // the order they make them.
      if tokenizer.matches(token, "Sphere") {
        if state.objects.count == state.declared.value {
          throw tooMany(state.declared, "Group", "numObjects", "object", token)
        }
        state.objects.append(.sphere(try parseSphere(material: state.material)))
        continue
      }
      if tokenizer.matches(token, "MaterialIndex") {
        let valueToken = peekStart()
        let value = try wholeNumber("MaterialIndex")
        pendingMaterialChecks.append((value, valueToken))
        state.material = value
        continue
      }
      guard Self.objectKinds.contains(where: { tokenizer.matches(token, $0) })
      else {
        throw unexpected(
          token, expected: "an object",
          choices: Self.objectKinds.map { "\($0)" } + ["MaterialIndex"])
      }
      if state.objects.count == state.declared.value {
        throw tooMany(state.declared, "Group", "numObjects", "object", token)
      }
      state.objects.append(
        try parseObject(token, depth: state.depth, material: state.material))
    }
  }

  // MARK: - Reading a large group on two threads

  /// Groups declaring fewer objects are read on one thread.
  static let concurrentGroupSize = 20_000
  /// Nor is a file split where less than this is left to read.
  static let concurrentBytes = 1 << 20

  /// Where a second thread can start reading a large group's objects: the
  /// start of the line nearest the middle of what is left of the file.
  /// Nothing spans a line break (a comment ends there), so the tokens from
  /// there on are the ones the sequential parse reads.
  private func speculationPoint(declared: Int) -> Int? {
    let start = tokenizer.position.index
    let bytes = tokenizer.bytes
    guard declared >= concurrentFrom.groupSize,
      bytes.count - start >= concurrentFrom.bytes,
      sysconf(Int32(_SC_NPROCESSORS_ONLN)) > 1
    else { return nil }
    var index = start + (bytes.count - start) / 2
    while index < bytes.count && bytes[index] != UInt8(ascii: "\n") {
      index += 1
    }
    return index + 1 < bytes.count ? index + 1 : nil
  }

  /// Reads the group up to `split` here while another thread reads plain
  /// spheres and material indices from `split` on (see `SphereRun`); when
  /// this thread arrives there at the group's level, it takes the other's
  /// objects and goes on from where the other stopped.
  ///
  /// Whatever the other thread read, the result and every error are the
  /// sequential parse's: the other thread stops before anything it does
  /// not read exactly as this one would (anything but a well-formed
  /// sphere or `MaterialIndex`), and its objects are taken only when this
  /// thread reaches the same token at the group's level with room for
  /// them under `numObjects`; otherwise this thread reads on itself.
  private mutating func parseObjectsAlongside(
    _ state: inout GroupState, from split: Int
  ) throws(SceneError) -> GroupProgress {
    var run = SphereRun(
      bytes: tokenizer.source, file: file, from: split,
      capacity: state.declared.value - state.objects.count)
    run.parser.readsPlainSpheres = readsPlainSpheres
    var outcome: Result<GroupProgress, SceneError> = .success(.spliced)
    withUnsafeMutablePointer(to: &self) { parser in
      withUnsafeMutablePointer(to: &state) { state in
        withUnsafeMutablePointer(to: &run) { run in
          withUnsafeMutablePointer(to: &outcome) { outcome in
            let shared = Shared((parser, state, run, outcome))
            DispatchQueue.concurrentPerform(iterations: 2) { thread in
              let (parser, state, run, outcome) = shared.value
              if thread == 0 {
                do throws(SceneError) {
                  outcome.pointee = .success(
                    try parser.pointee.parseObjects(
                      &state.pointee, first: nil, limit: split))
                } catch {
                  outcome.pointee = .failure(error)
                }
              } else {
                run.pointee.read()
              }
            }
          }
        }
      }
    }
    let progress = try outcome.get()
    guard case .reached(let token) = progress, let runFirst = run.first,
      token.start == runFirst.start, !run.spheres.isEmpty,
      run.spheres.count <= state.declared.value - state.objects.count
    else { return progress }
    // The other parser counted lines from 1 at `split`.
    let lines = token.line - runFirst.line
    let inherited = state.material
    for (offset, var sphere) in run.spheres.enumerated() {
      if offset < run.inheritingCount { sphere.materialIndex = inherited }
      state.objects.append(.sphere(sphere))
    }
    for var check in run.parser.pendingMaterialChecks {
      check.token.line += lines
      pendingMaterialChecks.append(check)
    }
    if run.sawMaterialIndex {
      state.material = run.parser.currentMaterial
    }
    splicedObjects += run.spheres.count
    var resume = run.stop
    resume.line += lines
    tokenizer.position = resume
    return .spliced
  }

  /// Plain spheres and `MaterialIndex` lines read from a point in the
  /// middle of a group, by a parser of its own, until anything else: the
  /// group's `}`, another kind of object, or an error.
  struct SphereRun {
    var parser: SceneParser
    let capacity: Int
    /// The first token read, if any.
    var first: SceneToken?
    /// Spheres rather than objects: plain values, which are copied and
    /// freed without a call per element.
    var spheres: [Sphere<Double>] = []
    /// How many spheres come before the first `MaterialIndex`, and so take
    /// the material current where the run starts.
    var inheritingCount = 0
    var sawMaterialIndex = false
    /// Where the first token not read starts.
    var stop: SceneTokenizer.Position

    init(bytes: SceneBytes, file: String, from split: Int, capacity: Int) {
      parser = SceneParser(
        bytes: bytes, file: file, options: .init(style: .course))
      parser.tokenizer.position = SceneTokenizer.Position(
        index: split, line: 1, lineStart: split)
      self.capacity = capacity
      stop = parser.tokenizer.position
    }

    mutating func read() {
      spheres.reserveCapacityOnHugePages(
        Swift.min(
          capacity,
          (parser.tokenizer.bytes.count - stop.index)
            / SceneParser.minimumObjectLength))
      // A placeholder no `MaterialIndex` can give.
      parser.currentMaterial = -1
      while spheres.count < capacity {
        let token = parser.tokenizer.next()
        if first == nil { first = token }
        guard token.kind == .word,
          token.end - token.start <= SceneParser.maximumWordLength
        else { return }
        if parser.tokenizer.matches(token, "Sphere") {
          guard
            let sphere = try? parser.parseSphere(
              material: parser.currentMaterial)
          else { return }
          spheres.append(sphere)
          if !sawMaterialIndex { inheritingCount += 1 }
        } else if parser.tokenizer.matches(token, "MaterialIndex") {
          let valueToken = parser.peekStart()
          guard let value = try? parser.wholeNumber("MaterialIndex") else {
            return
          }
          parser.pendingMaterialChecks.append((value, valueToken))
          parser.currentMaterial = value
          sawMaterialIndex = true
        } else {
          return
        }
        stop = parser.tokenizer.position
      }
    }
  }

  static let objectKinds: [StaticString] = [
    "Sphere", "Plane", "Triangle", "TriangleMesh", "Group", "Transform",
  ]

  /// The object starting at `token`, one of `objectKinds`; groups and
  /// transforms count towards the nesting limit.
  private mutating func parseObject(
    _ token: SceneToken, depth: Int, material: Int
  ) throws(SceneError) -> SceneObject<Double> {
    if tokenizer.matches(token, "Sphere") {
      return .sphere(try parseSphere(material: material))
    }
    if tokenizer.matches(token, "Plane") {
      return .plane(try parsePlane(material: material))
    }
    if tokenizer.matches(token, "Triangle") {
      return .triangle(try parseTriangle(material: material))
    }
    if tokenizer.matches(token, "TriangleMesh") {
      return try parseTriangleMesh(material: material)
    }
    guard depth < Self.maximumGroupDepth else {
      throw error(
        at: token,
        "Groups are nested more than \(Self.maximumGroupDepth) deep")
    }
    if tokenizer.matches(token, "Group") {
      return .group(try parseGroup(depth: depth + 1, material: material))
    }
    return .transform(
      try parseTransform(token, depth: depth + 1, material: material))
  }

  /// `Transform { operations… object }`. Translate, Scale, UniformScale and
  /// the rotations (degrees) compose as the course's starter code does,
  /// matrix = matrix·next, so the last listed acts on the object first;
  /// `Matrix4f` lists 16 numbers column by column (OpenGL order) and
  /// composes on the left, matrix = next·matrix, also as the starter code.
  private mutating func parseTransform(
    _ start: SceneToken, depth: Int, material: Int
  ) throws(SceneError) -> Transform<Double> {
    try expect(.open, "'{' after Transform")
    openTransforms += 1
    defer { openTransforms -= 1 }
    var matrix = Matrix4<Double>.identity
    var object: SceneObject<Double>?
    while true {
      let token = try next()
      switch token.kind {
      case .close:
        guard let object else {
          throw error(at: token, "Transform has no object to transform")
        }
        // Overflowing operations (`Translate 1e308 0 0` twice) leave
        // infinities, for which "no inverse" would be the wrong reason.
        guard matrix.rowMajorEntries.allSatisfy(\.isFinite) else {
          throw error(
            at: start,
            "the Transform's matrix overflows: its entries are not all finite")
        }
        guard let transform = Transform(matrix: matrix, object: object) else {
          throw error(
            at: start, "the Transform's matrix has no inverse (a scale of 0?)")
        }
        if openTransforms == 1 {
          try checkMovedGeometry(transform, start)
        }
        return transform
      case .end, .open:
        throw unexpectedEnd(token, in: "Transform")
      case .word:
        break
      }
      if Self.objectKinds.contains(where: { tokenizer.matches(token, $0) }) {
        guard object == nil else {
          throw error(
            at: token, "a Transform holds one object; group several in a Group")
        }
        object = try parseObject(token, depth: depth, material: material)
        continue
      }
      guard object == nil else {
        throw error(
          at: token,
          "transform operations come before the object, found '\(text(token))'")
      }
      switch text(token) {
      case "Translate": matrix = matrix * .translation(try vector())
      case "Scale":
        let at = peekStart()
        let factors = try vector()
        guard factors.x != 0, factors.y != 0, factors.z != 0 else {
          throw error(at: at, "'Scale' factors must not be 0")
        }
        matrix = matrix * .scale(factors)
      case "UniformScale":
        let at = peekStart()
        let factor = try number()
        guard factor != 0 else {
          throw error(at: at, "'UniformScale' must not be 0")
        }
        matrix = matrix * .uniformScale(factor)
      case "XRotate": matrix = matrix * .rotationX(degrees: try number())
      case "YRotate": matrix = matrix * .rotationY(degrees: try number())
      case "ZRotate": matrix = matrix * .rotationZ(degrees: try number())
      case "Rotate":
        let at = peekStart()
        let axis = try vector()
        guard axis.maxMagnitude > 0 else {
          throw error(at: at, "'Rotate' needs a non-zero axis")
        }
        matrix = matrix * .rotation(axis: axis, degrees: try number())
      case "Matrix4f":
        var entries: [Double] = []
        for _ in 0..<16 { entries.append(try number()) }
        matrix = Matrix4(columns: entries) * matrix
      default:
        throw unexpected(
          token, expected: "a transform operation or an object",
          choices: [
            "Translate", "Scale", "UniformScale", "XRotate", "YRotate",
            "ZRotate",
            "Rotate", "Matrix4f",
          ] + Self.objectKinds.map { "\($0)" })
      }
    }
  }

  /// Refuses geometry that a Transform takes beyond Double's range: each
  /// number of the file is finite, but a product of finite matrices, or a
  /// finite matrix applied to a point, need not be (`UniformScale 1e300`
  /// of `offset 1e300`), nor need a scaled radius stay above 0. The render
  /// would otherwise meet infinities and NaN normals.
  private func checkMovedGeometry(
    _ transform: Transform<Double>, _ start: SceneToken
  ) throws(SceneError) {
    guard Self.movedGeometryIsFinite(transform) else {
      throw error(at: start, Self.movedGeometryMessage)
    }
  }

  static let movedGeometryMessage =
    "the Transform takes its object beyond Double's range: a coordinate, "
    + "offset or normal is no longer finite, or a radius becomes 0"

  /// Whether every primitive under `transform`, moved, is finite (and
  /// every sphere keeps a positive radius).
  static func movedGeometryIsFinite(_ transform: Transform<Double>) -> Bool {
    let moved = Group([.transform(transform)]).flattened()
    return
      moved.spheres.allSatisfy {
        $0.center.isFinite && $0.radius.isFinite && $0.radius > 0
      }
      && moved.planes.allSatisfy { $0.normal.isFinite && $0.offset.isFinite }
      && moved.triangles.allSatisfy { triangle in
        triangle.v0.isFinite && triangle.v1.isFinite && triangle.v2.isFinite
          && (triangle.vertexNormals.map {
            $0.n0.isFinite && $0.n1.isFinite && $0.n2.isFinite
          } ?? true)
      }
      && moved.transformedSpheres.allSatisfy {
        $0.matrix.rowMajorEntries.allSatisfy(\.isFinite)
          && $0.inverse.rowMajorEntries.allSatisfy(\.isFinite)
      }
  }

  private mutating func parseTriangle(material: Int) throws(SceneError)
    -> Triangle<Double>
  {
    var vertices: [Vector3<Double>?] = [nil, nil, nil]
    let close = try parseFields(
      "Triangle", ["vertex0", "vertex1", "vertex2"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      let index = field == "vertex0" ? 0 : field == "vertex1" ? 1 : 2
      vertices[index] = try parser.vector()
    }
    guard let v0 = vertices[0], let v1 = vertices[1], let v2 = vertices[2]
    else {
      throw missing(
        "Triangle",
        [
          ("vertex0", vertices[0] != nil), ("vertex1", vertices[1] != nil),
          ("vertex2", vertices[2] != nil),
        ], close)
    }
    return Triangle(v0, v1, v2, materialIndex: material)
  }

  /// `TriangleMesh { obj_file PATH }`, the path relative to the scene
  /// file's folder; the mesh is one object, a group of its triangles.
  private mutating func parseTriangleMesh(material: Int) throws(SceneError)
    -> SceneObject<Double>
  {
    var path: (String, SceneToken)?
    let close = try parseFields(
      "TriangleMesh", ["obj_file"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      path = try parser.path(after: field)
    }
    guard let (relative, token) = path else {
      throw missing("TriangleMesh", [("obj_file", false)], close)
    }
    let resolved = resolved(relative)
    let textured = parsedMaterials.map {
      $0.indices.contains(material) && $0[material].texturePath != nil
    }
    do {
      let mesh = try MeshLoader.load(
        resolved, materialIndex: material, textured: textured ?? false,
        normals: options.meshNormals)
      meshFiles.append(resolved)
      if !mesh.hasTextureCoordinates {
        meshesWithoutTextureCoordinates.append((material, token, resolved))
      }
      return mesh.object
    } catch {
      switch error {
      case .inFile(let inner): throw inner
      case .atReference(let message): throw self.error(at: token, message)
      }
    }
  }

  /// The path after `field`, as written: `text` escapes control characters,
  /// which would name another file.
  private mutating func path(
    after field: String
  ) throws(SceneError) -> (String, SceneToken) {
    let token = try next()
    guard token.kind == .word else {
      throw error(at: token, "expected a file's path after '\(field)'")
    }
    return (tokenizer.text(of: token), token)
  }

  /// `relative` against the scene file's folder; absolute paths as given.
  private func resolved(_ relative: String) -> String {
    if relative.hasPrefix("/") { return relative }
    guard let slash = file.lastIndex(of: "/") else { return relative }
    return String(file[...slash]) + relative
  }

  /// The hot path of large scenes: keywords are compared as bytes, and
  /// nothing is allocated. The same checks and messages as `parseFields`
  /// with `positive` for the radius. The plain form, nearly every sphere
  /// of a generated scene, is read in one pass first; whatever that pass
  /// leaves, errors included, is read token by token.
  private mutating func parseSphere(material: Int) throws(SceneError) -> Sphere<
    Double
  > {
    let start = tokenizer.position
    if readsPlainSpheres, let (center, radius) = tokenizer.plainSphere() {
      if radius > 0 {
        return Sphere(center: center, radius: radius, materialIndex: material)
      }
      // The error at the radius comes from the reading below.
      tokenizer.position = start
    }
    try expect(.open, "'{' after Sphere")
    var center: Vector3<Double>?
    var radius: Double?
    while true {
      let token = try next()
      switch token.kind {
      case .close:
        guard let center, let radius else {
          throw missing(
            "Sphere", [("center", center != nil), ("radius", radius != nil)],
            token)
        }
        return Sphere(center: center, radius: radius, materialIndex: material)
      case .end, .open:
        throw unexpectedEnd(token, in: "Sphere")
      case .word:
        if tokenizer.matches(token, "center") {
          guard center == nil else {
            throw error(at: token, "'center' is given twice in Sphere")
          }
          center = try vector()
        } else if tokenizer.matches(token, "radius") {
          guard radius == nil else {
            throw error(at: token, "'radius' is given twice in Sphere")
          }
          radius = try positive("radius")
        } else {
          throw unexpected(
            token, expected: "a field of Sphere", choices: ["center", "radius"])
        }
      }
    }
  }

  private mutating func parsePlane(material: Int) throws(SceneError) -> Plane<
    Double
  > {
    var normal: Vector3<Double>?
    var offset: (Double, SceneToken)?
    let close = try parseFields(
      "Plane", ["normal", "offset"]
    ) { (parser: inout SceneParser, field: String) throws(SceneError) in
      if field == "normal" {
        normal = try parser.nonZeroVector(field)
      } else {
        let token = parser.peekStart()
        offset = (try parser.number(), token)
      }
    }
    guard let normal, let offset else {
      throw missing(
        "Plane", [("normal", normal != nil), ("offset", offset != nil)], close)
    }
    let plane = Plane(normal: normal, offset: offset.0, materialIndex: material)
    // Dividing by the normal's length overflows for a tiny normal and a
    // large offset (`normal 0 0 1e-150  offset 1e300`): the plane lies
    // beyond Double's range, and an infinite offset must not reach a render.
    guard plane.offset.isFinite else {
      throw error(
        at: offset.1,
        "the plane is too far from the origin: offset \(text(offset.1)) divided "
          + "by the normal's length is not a finite number")
    }
    return plane
  }

  // MARK: - Fields and values

  /// Reads `{ field value … }`, each of `fields` at most once, calling `read`
  /// to parse each value; returns the closing brace, for messages about
  /// missing fields.
  private mutating func parseFields(
    _ block: String, _ fields: [StaticString],
    read: (inout SceneParser, String) throws(SceneError) -> Void
  ) throws(SceneError) -> SceneToken {
    try expect(.open, "'{' after \(block)")
    // A mask rather than an array: no block has more than a few fields,
    // and an allocation per block showed in the parse of large scenes.
    var seen: UInt64 = 0
    while true {
      let token = try next()
      switch token.kind {
      case .close:
        return token
      case .end, .open:
        throw unexpectedEnd(token, in: block)
      case .word:
        guard
          let index = fields.firstIndex(where: { tokenizer.matches(token, $0) })
        else {
          throw unexpected(
            token, expected: "a field of \(block)",
            choices: fields.map { "\($0)" })
        }
        guard seen & (1 << index) == 0 else {
          throw error(
            at: token, "'\(fields[index])' is given twice in \(block)")
        }
        seen |= 1 << index
        try read(&self, "\(fields[index])")
      }
    }
  }

  /// The next token; a word longer than `maximumWordLength` is an error.
  private mutating func next() throws(SceneError) -> SceneToken {
    let token = tokenizer.next()
    let length = token.end - token.start
    guard token.kind != .word || length <= Self.maximumWordLength else {
      var head = token
      head.end = token.start + 24
      throw error(
        at: token,
        "a word of \(length) bytes ('\(text(head))…') is longer than the "
          + "limit of \(Self.maximumWordLength) bytes")
    }
    return token
  }

  /// The position of the next token, without consuming it: a copy of the
  /// tokenizer is cheap, since its bytes are shared.
  private func peekStart() -> SceneToken {
    var copy = tokenizer
    return copy.next()
  }

  private mutating func number() throws(SceneError) -> Double {
    try numberAndToken().value
  }

  private mutating func numberAndToken() throws(SceneError) -> (
    value: Double, token: SceneToken
  ) {
    let token = try next()
    guard let value = tokenizer.number(token) else {
      throw error(at: token, "expected a number, found '\(text(token))'")
    }
    guard value.isFinite else {
      throw error(at: token, "expected a finite number, found '\(text(token))'")
    }
    return (value, token)
  }

  private mutating func vector() throws(SceneError) -> Vector3<Double> {
    let x = try number()
    let y = try number()
    let z = try number()
    return Vector3(x, y, z)
  }

  private mutating func nonZeroVector(_ field: String) throws(SceneError)
    -> Vector3<Double>
  {
    let start = peekStart()
    let value = try vector()
    guard value.maxMagnitude > 0 else {
      throw error(at: start, "'\(field)' must not be the zero vector")
    }
    return value
  }

  private mutating func color(_ field: String) throws(SceneError) -> RGB<Double>
  {
    let start = peekStart()
    let value = try vector()
    guard value.x >= 0 && value.y >= 0 && value.z >= 0 else {
      throw error(at: start, "'\(field)' components must not be negative")
    }
    return value
  }

  private mutating func positive(_ field: String) throws(SceneError) -> Double {
    let (value, token) = try numberAndToken()
    guard value > 0 else {
      throw error(
        at: token, "'\(field)' must be positive, found \(text(token))")
    }
    return value
  }

  private mutating func nonNegative(_ field: String) throws(SceneError)
    -> Double
  {
    let token = peekStart()
    let value = try number()
    guard value >= 0 else {
      throw error(
        at: token, "'\(field)' must not be negative, found \(text(token))")
    }
    return value
  }

  private mutating func wholeNumber(_ field: String) throws(SceneError) -> Int {
    let token = peekStart()
    let value = try number()
    guard value >= 0, value == value.rounded(), value < 1e15 else {
      throw error(
        at: token, "'\(field)' must be a whole number ≥ 0, found \(text(token))"
      )
    }
    return Int(value)
  }

  // MARK: - Counts

  private mutating func count(
    _ field: StaticString, in block: String
  ) throws(SceneError) -> (value: Int, token: SceneToken) {
    let token = try next()
    guard tokenizer.matches(token, field) else {
      throw error(
        at: token,
        "expected '\(field)' at the start of \(block), found '\(text(token))'")
    }
    let valueToken = peekStart()
    return (try wholeNumber("\(field)"), valueToken)
  }

  private func checkCount(
    _ found: Int, _ declared: (value: Int, token: SceneToken), _ block: String,
    _ field: String, _ noun: String, _ close: SceneToken
  ) throws(SceneError) {
    guard found == declared.value else {
      throw error(
        at: close,
        "\(block) has \(found) \(noun)\(found == 1 ? "" : "s") but \(field) "
          + "(line \(declared.token.line)) says \(declared.value)")
    }
  }

  private func tooMany(
    _ declared: (value: Int, token: SceneToken), _ block: String,
    _ field: String, _ noun: String, _ token: SceneToken
  ) -> SceneError {
    error(
      at: token,
      "\(block) has more \(noun)s than \(field) (line \(declared.token.line)) "
        + "says (\(declared.value))")
  }

  // MARK: - Messages

  /// The token as messages quote it and keywords are compared with it:
  /// control characters and line separators are escaped (`\u{1B}`), so that
  /// a message stays on one line and cannot drive the terminal showing it.
  private func text(_ token: SceneToken) -> String {
    Self.escaped(tokenizer.text(of: token))
  }

  /// `raw` with control characters and line separators escaped.
  public static func escaped(_ raw: String) -> String {
    guard raw.unicodeScalars.contains(where: needsEscape) else { return raw }
    var escaped = String.UnicodeScalarView()
    for scalar in raw.unicodeScalars {
      if needsEscape(scalar) {
        let hex = String(scalar.value, radix: 16, uppercase: true)
        escaped.append(contentsOf: "\\u{\(hex)}".unicodeScalars)
      } else {
        escaped.append(scalar)
      }
    }
    return String(escaped)
  }

  /// C0 and C1 controls, DEL, and the Unicode line and paragraph separators.
  private static func needsEscape(_ scalar: Unicode.Scalar) -> Bool {
    scalar.value < 0x20 || (0x7F...0x9F).contains(scalar.value)
      || scalar.value == 0x2028 || scalar.value == 0x2029
  }

  private func error(at token: SceneToken, _ message: String) -> SceneError {
    SceneError(
      file: file, line: token.line, column: token.column, message: message)
  }

  private mutating func expect(
    _ kind: SceneToken.Kind, _ what: String
  ) throws(SceneError) {
    let token = try next()
    guard token.kind == kind else {
      throw error(
        at: token,
        "expected \(what), found \(token.kind == .end ? "end of file" : "'\(text(token))'")"
      )
    }
  }

  private func unexpectedEnd(_ token: SceneToken, in block: String)
    -> SceneError
  {
    token.kind == .end
      ? error(at: token, "unexpected end of file: \(block) is missing its '}'")
      : error(at: token, "unexpected '\(text(token))' in \(block)")
  }

  /// Names an unsupported block as such, otherwise suggests the nearest of
  /// `choices`.
  private func unexpected(
    _ token: SceneToken, expected: String, choices: [String]
  ) -> SceneError {
    let word = text(token)
    if Self.unsupportedBlocks.contains(word) {
      return error(
        at: token,
        "'\(word)' is not supported: raytrace renders spheres and planes with a "
          + "PerspectiveCamera")
    }
    if tokenizer.number(token) != nil {
      return error(at: token, "expected \(expected), found the number \(word)")
    }
    var message = "expected \(expected), found '\(word)'"
    // Suggested from the bytes as written: "Sph", NUL, "ere" is one edit
    // from `Sphere`, its escaped form `Sph\u{0}ere` five.
    if let suggestion = nearest(to: tokenizer.text(of: token), in: choices) {
      message += "; did you mean '\(suggestion)'?"
    } else {
      message +=
        " (expected one of \(choices.map { "'\($0)'" }.joined(separator: ", ")))"
    }
    return error(at: token, message)
  }

  private func missing(
    _ block: String, _ fields: [(String, Bool)], _ close: SceneToken
  ) -> SceneError {
    let absent = fields.filter { !$0.1 }.map { "'\($0.0)'" }
    return error(
      at: close, "\(block) is missing \(absent.joined(separator: " and "))")
  }
}

/// The choice within edit distance ⌈length/3⌉ of `word`, case ignored, if any.
func nearest(to word: String, in choices: [String]) -> String? {
  let lowered = Array(word.lowercased().utf8)
  var best: (choice: String, distance: Int)?
  for choice in choices {
    let distance = editDistance(lowered, Array(choice.lowercased().utf8))
    if distance <= max(1, (choice.utf8.count + 2) / 3),
      distance < (best?.distance ?? .max)
    {
      best = (choice, distance)
    }
  }
  return best?.choice
}

/// Levenshtein distance, two rows at a time.
func editDistance(_ a: [UInt8], _ b: [UInt8]) -> Int {
  if a.isEmpty { return b.count }
  var previous = Array(0...b.count)
  var current = previous
  for i in 1...a.count {
    current[0] = i
    for j in stride(from: 1, through: b.count, by: 1) {
      let substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)
      current[j] = min(substitution, previous[j] + 1, current[j - 1] + 1)
    }
    swap(&previous, &current)
  }
  return previous[b.count]
}

/// 4 GiB: a scene of tens of millions of spheres, or a mesh of a hundred
/// million triangles.
let maximumFileSize = 1 << 32

struct FileReadError: Error {
  var reason: String
}

/// The whole file in one read; errors carry the system's reason.
///
/// Only regular files up to `maximumFileSize` are read: a device such as
/// /dev/zero, a FIFO or a directory named as a scene or a mesh would
/// otherwise hang the program or exhaust its memory.
func readFile(_ path: String) throws(FileReadError) -> [UInt8] {
  let (descriptor, size) = try openRegularFile(path)
  return try readOpenFile(descriptor, expected: size)
}

/// Opens `path` for reading if it is a regular file of at most
/// `maximumFileSize` bytes: its descriptor, and its size as reported.
func openRegularFile(
  _ path: String
) throws(FileReadError) -> (descriptor: Int32, size: Int) {
  // Non-blocking: opening a FIFO for reading would otherwise wait for a
  // writer, forever, before fstat below could refuse it. The flag changes
  // nothing for the regular files that are read.
  let descriptor = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC)
  guard descriptor >= 0 else {
    throw FileReadError(
      reason: "cannot open the file: \(String(cString: strerror(errno)))")
  }
  var status = stat()
  guard fstat(descriptor, &status) == 0 else {
    let reason = String(cString: strerror(errno))
    close(descriptor)
    throw FileReadError(reason: "cannot read the file: \(reason)")
  }
  guard (status.st_mode & S_IFMT) == S_IFREG else {
    close(descriptor)
    throw FileReadError(reason: "not a regular file")
  }
  guard Int(status.st_size) <= maximumFileSize else {
    close(descriptor)
    throw FileReadError(
      reason:
        "the file is \(status.st_size) bytes; the limit is \(maximumFileSize)")
  }
  return (descriptor, Int(status.st_size))
}

/// Reads the file open at `descriptor` to its end, and closes it.
func readOpenFile(
  _ descriptor: Int32, expected: Int
) throws(FileReadError) -> [UInt8] {
  guard let handle = fdopen(descriptor, "rb") else {
    let reason = String(cString: strerror(errno))
    close(descriptor)
    throw FileReadError(reason: "cannot open the file: \(reason)")
  }
  defer { fclose(handle) }
  // Straight into the array when the size is right: a 72 MB scene was
  // otherwise copied once more, chunk by chunk. A file that grows while it
  // is read goes on in chunks.
  var failed = false
  var bytes = [UInt8](unsafeUninitializedCapacity: expected) { buffer, count in
    count = fread(buffer.baseAddress, 1, expected, handle)
    failed = count < expected && ferror(handle) != 0
  }
  var chunk = [UInt8](
    repeating: 0, count: failed || bytes.count < expected ? 0 : 1 << 16)
  while !failed && !chunk.isEmpty {
    let read = chunk.withUnsafeMutableBytes {
      fread($0.baseAddress, 1, $0.count, handle)
    }
    if read > 0 { bytes.append(contentsOf: chunk[0..<read]) }
    if read < chunk.count {
      failed = ferror(handle) != 0
      break
    }
  }
  if failed {
    throw FileReadError(
      reason: "cannot read the file: \(String(cString: strerror(errno)))")
  }
  return bytes
}
