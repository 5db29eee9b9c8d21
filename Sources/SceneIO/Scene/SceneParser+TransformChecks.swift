import Geometry
import SceneDescription
import Numerics

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
        .with(options.precision.remedy)
    }
  }

  static func movedGeometryMessage(_ precision: Precision) -> String {
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
    _ transform: Transform<Double>, _ precision: Precision
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

  /// Whether every primitive under `transform`, moved, is finite in
  /// `precision` (and every sphere keeps a radius it holds, above 0).
  static func movedGeometryIsFinite(
    _ transform: Transform<Double>, _ precision: Precision = .double
  ) -> Bool {
    let moved = Group([.transform(transform)]).flattened()
    func finite(_ v: Vector3<Double>) -> Bool {
      precision.isFinite(v.x) && precision.isFinite(v.y)
        && precision.isFinite(v.z)
    }
    return
      moved.spheres.allSatisfy {
        finite($0.center) && $0.radius > 0 && precision.holds($0.radius)
      }
      && moved.planes.allSatisfy {
        finite($0.normal) && precision.isFinite($0.offset)
      }
      && moved.triangles.allSatisfy { triangle in
        finite(triangle.v0) && finite(triangle.v1) && finite(triangle.v2)
          && (triangle.vertexNormals.map {
            finite($0.n0) && finite($0.n1) && finite($0.n2)
          } ?? true)
      }
      && moved.transformedSpheres.allSatisfy {
        $0.matrix.rowMajorEntries.allSatisfy(precision.isFinite)
          && $0.inverse.rowMajorEntries.allSatisfy(precision.isFinite)
      }
  }
}
