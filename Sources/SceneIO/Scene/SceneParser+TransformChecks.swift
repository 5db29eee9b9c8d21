import Geometry
import SceneDescription

/// What a Transform makes of its object, checked against the render's
/// precision: its matrix and inverse, and the moved geometry. Shared by
/// both scene formats.
extension SceneParser {
  /// Refuses geometry that a Transform takes beyond Double's range: each
  /// number of the file is finite, but a product of finite matrices, or a
  /// finite matrix applied to a point, need not be (`UniformScale 1e300`
  /// of `offset 1e300`), nor need a scaled radius stay above 0. The render
  /// would otherwise meet infinities and NaN normals.
  func checkMovedGeometry(
    _ transform: Transform<Double>, _ start: SceneToken
  ) throws(SceneError) {
    guard Self.movedGeometryIsFinite(transform, options.precision) else {
      throw error(at: start, Self.movedGeometryMessage(options.precision))
        .exceeding(options.precision)
    }
  }

  static func movedGeometryMessage(_ precision: NumberRange) -> String {
    switch precision {
    case .double:
      "the Transform takes its object beyond Double's range: a coordinate, "
        + "offset or normal is no longer finite, or a radius becomes 0"
    case .float:
      "the Transform takes its object beyond float's range: a coordinate, "
        + "offset or normal is no longer finite, or a radius becomes 0 or "
        + "subnormal"
    }
  }

  /// Why the matrix or the inverse of `transform` (finite in Double)
  /// cannot be held in `precision`: an entry beyond its finite range, which
  /// no rescaling of the scene by a power of two saves (the linear part is
  /// dimensionless). Nil when both fit.
  static func matrixProblem(
    _ transform: Transform<Double>, _ precision: NumberRange
  ) -> String? {
    for (name, matrix) in [
      ("matrix", transform.matrix), ("inverse", transform.inverse),
    ] {
      if let entry = matrix.rowMajorEntries.first(where: {
        !precision.isFinite($0)
      }) {
        return "the Transform's \(name) overflows: its entry \(entry) is "
          + precision.overflowSuffix()
      }
    }
    return nil
  }

  /// Whether every primitive under `transform`, placed as a render
  /// places it (`Group.forEachPlaced`), is finite in `precision` (and
  /// every sphere keeps a radius it holds, above 0). The one place the
  /// readers look at a scene object's kind.
  static func movedGeometryIsFinite(
    _ transform: Transform<Double>, _ precision: NumberRange = .double
  ) -> Bool {
    func finite(_ v: Vector3<Double>) -> Bool {
      precision.isFinite(v.x) && precision.isFinite(v.y)
        && precision.isFinite(v.z)
    }
    func finite(_ matrix: Matrix4<Double>) -> Bool {
      matrix.rowMajorEntries.allSatisfy(precision.isFinite)
    }
    func finite(_ triangle: Triangle<Double>) -> Bool {
      finite(triangle.v0) && finite(triangle.v1) && finite(triangle.v2)
        && (triangle.vertexNormals.map {
          finite($0.n0) && finite($0.n1) && finite($0.n2)
        } ?? true)
    }
    var isFinite = true
    Group([.transform(transform)]).forEachPlaced { object, placement in
      guard isFinite, let (matrix, inverse) = placement else { return }
      switch object {
      case .sphere(let sphere):
        if let placed = sphere.placed(by: matrix) {
          isFinite =
            finite(placed.center) && placed.radius > 0
            && precision.holds(placed.radius)
        } else {
          isFinite = finite(matrix) && finite(inverse)
        }
      case .plane(let plane):
        let placed = plane.placed(by: matrix)
        isFinite = finite(placed.normal) && precision.isFinite(placed.offset)
      case .triangle(let triangle):
        isFinite = finite(triangle.moved(by: matrix))
      case .mesh(let mesh):
        isFinite = mesh.moved(by: matrix).allSatisfy(finite)
      case .shape:
        // Tested in the world's units through its own conformance.
        break
      case .group, .transform:
        preconditionFailure("Group.forEachPlaced yields neither")
      }
    }
    return isFinite
  }
}
