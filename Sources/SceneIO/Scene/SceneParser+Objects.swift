import Geometry
import SceneDescription
import PlatformSupport

/// The objects of a group: spheres, planes, triangles, meshes, transforms
/// and nested groups, each checked as it is read.
extension SceneParser {
  /// A group's objects take the material set by the last `MaterialIndex`
  /// before them; a nested group starts with its parent's current material.
  mutating func parseGroup(
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
  mutating func parseObjects(
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
      if !options.shapes.isEmpty,
        let kind = options.shapes.first(where: {
          tokenizer.text(of: token) == $0.name
        })
      {
        if state.objects.count == state.declared.value {
          throw tooMany(state.declared, "Group", "numObjects", "object", token)
        }
        state.objects.append(
          try parseShape(kind, token, material: state.material))
        continue
      }
      guard Self.objectKinds.contains(where: { tokenizer.matches(token, $0) })
      else {
        throw unexpected(
          token, expected: "an object",
          choices: Self.objectKinds.map { "\($0)" } + options.shapes.map(\.name)
            + ["MaterialIndex"])
      }
      if state.objects.count == state.declared.value {
        throw tooMany(state.declared, "Group", "numObjects", "object", token)
      }
      state.objects.append(
        try parseObject(token, depth: state.depth, material: state.material))
    }
  }

  static let objectKinds: [StaticString] = [
    "Sphere", "Plane", "Triangle", "TriangleMesh", "Group", "Transform",
  ]

  /// The object starting at `token`, one of `objectKinds`; groups and
  /// transforms count towards the nesting limit.
  mutating func parseObject(
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
        "Groups and Transforms are nested more than "
          + "\(Self.maximumGroupDepth) deep")
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
  mutating func parseTransform(
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
        if let problem = Self.matrixProblem(transform, options.precision) {
          throw error(at: start, problem).exceeding(options.precision)
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
      // A shape of one's own (SceneOptions.shapes) as in a Group.
      let ownShape =
        options.shapes.isEmpty
        ? nil
        : options.shapes.first { tokenizer.text(of: token) == $0.name }
      if ownShape != nil
        || Self.objectKinds.contains(where: { tokenizer.matches(token, $0) })
      {
        guard object == nil else {
          throw error(
            at: token, "a Transform holds one object; group several in a Group")
        }
        if let ownShape {
          object = try parseShape(ownShape, token, material: material)
        } else {
          object = try parseObject(token, depth: depth, material: material)
        }
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
          ] + Self.objectKinds.map { "\($0)" } + options.shapes.map(\.name))
      }
    }
  }
}
