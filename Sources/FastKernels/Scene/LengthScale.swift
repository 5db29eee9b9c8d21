import Geometry
import SceneDescription
import PlatformSupport

/// Rescaling every length of a scene by a power of two, so that the
/// squares and products of its intersection tests stay inside the render
/// precision's range at any scale.
///
/// A unit-sphere scene scaled by s = 1e25 has |p|² − r² ≈ 1e50, which Float
/// cannot hold; scaled by 1e-25, its squares underflow to zero. Multiplying
/// every length (eye, centres, radii, plane offsets, vertices, the rows of a
/// transform's matrix) by 2^−k is exact while no result is subnormal, and
/// every test of the render (`SphereIntersection`, `PlaneIntersection`,
/// `TriangleIntersection`, the ellipsoids' local rays) is built from
/// +, −, ×, ÷ and √ with no length constant, so each of its roundings is
/// the rounding of the unscaled computation times a power of two: the
/// scaled scene's t′ is exactly t·2^−k, its normals (dimensionless) are
/// the same bits, and its hits and misses the same. The engines trace the
/// scaled scene and report t = t′·2^k; lights, shading and the camera's
/// ray directions are untouched.
///
/// The scale is judged from the eye: the records are offsets from it
/// (`CameraRelative`), so what their squares must hold is the scene's
/// lengths seen from the eye (offsets of centres and vertices, radii,
/// planes' distances, ellipsoids' reach), never the coordinates
/// themselves. A sphere of 1e-25 by an eye at x = 1 and the same sphere by
/// an eye at the origin are the same problem. The scale is chosen once per
/// render from the largest such length (`exponent`): 0, no rescaling at
/// all, while that length is within 2^±(E/4) of 1 for a precision whose
/// largest exponent is E (2^±31 for Float, 2^±255 for Double and wider
/// types, whose records are computed in Double first), which holds every
/// scene the project had before, so they run exactly as before. Beyond,
/// the scene is brought to lengths near 1, where a scene spanning up to
/// 2^(E/4) in relative size keeps its squares normal. Where the eye is so
/// far from the origin beside those lengths that its scaled coordinates
/// would leave that window (an eye at 1e300 beside specks of 1e-300), the
/// scene is first moved to the eye (`frame`), so that no coordinate, only
/// offsets, is scaled.
///
/// What rescaling cannot save: an object whose own lengths seen from the
/// eye span more than the precision's squares hold at the scale of its
/// distance (a sphere of radius 1e-25 three units from the eye in Float:
/// brought near 1, its radius squared is 10⁻⁵⁰; `problem`).
@usableFromInline
package enum LengthScale {
  /// The k of the scale 2^−k for `all` seen from `eye` in precision `S`:
  /// 0 when the largest length seen from the eye is within 2^±(E/4) of 1,
  /// else the exponent of that length, so that the scaled scene's largest
  /// length is in [1, 2).
  @usableFromInline
  package static func exponent<S: RayScalar>(
    _ all: Primitives<Double>, eye: Vector3<Double>, as _: S.Type
  ) -> Int {
    exponent(largestLength(all, eye: eye), as: S.self)
  }

  /// The largest length of the scene seen from `eye` (`Primitive.reach`):
  /// offsets of centres and vertices from the eye, radii, planes'
  /// distances from the eye, ellipsoids' reach. The eye's own coordinates
  /// are not lengths of the scene: they cancel in every record.
  static func largestLength(
    _ all: Primitives<Double>, eye: Vector3<Double>
  ) -> Double {
    var extent = Extent(eye: eye)
    extent.add(all)
    return extent.largest
  }

  /// The k of `exponent(_:eye:as:)` for a scene whose largest length is
  /// `largest`.
  static func exponent<S: RayScalar>(_ largest: Double, as _: S.Type)
    -> Int
  {
    guard largest > 0 else { return 0 }
    // An offset between coordinates of opposite signs near Double's limit
    // overflows: it is at least 2^1024, and 2^−1023 brings it near 1.
    let exponent = Int(Swift.min(largest, .greatestFiniteMagnitude).exponent)
    let limit = window(S.self)
    return (-limit...limit).contains(exponent) ? 0 : exponent
  }

  /// E/4 for the narrower of S's and Double's largest exponents E: the
  /// window 2^±(E/4) of lengths traced unscaled. Records are computed from
  /// the scene's Double values in Double (compensated, `CameraRelative`)
  /// before they are rounded to S, so a wider S (the Float80 reference) is
  /// computed at the same scale as a Double render.
  static func window<S: RayScalar>(_: S.Type) -> Int {
    Int(
      Swift.min(
        S.greatestFiniteMagnitude.exponent,
        S(Double.greatestFiniteMagnitude).exponent)) / 4
  }

  /// Calls `body` with every primitive of `object` in the world, placed
  /// as the render places them (`Group.flattened`). Shapes of one's own
  /// are tested in the world's units, at no scale: they have none.
  package static func forEachPrimitive(
    in object: SceneObject<Double>, _ body: (Primitive) -> Void
  ) {
    Group([object]).flattened().forEach(body)
  }

  /// One primitive of a flattened scene.
  package enum Primitive {
    case sphere(Sphere<Double>)
    case plane(Plane<Double>)
    case triangle(Triangle<Double>)
    case ellipsoid(TransformedSphere<Double>)

    /// Its largest length seen from `eye`, for the scale it is traced
    /// at: a sphere's centre's offset or its radius, a triangle's farthest
    /// vertex, a plane's distance, an ellipsoid's reach (in max-norm).
    package func reach(from eye: Vector3<Double>) -> Double {
      switch self {
      case .sphere(let sphere): sphere.reach(from: eye)
      case .plane(let plane): LengthScale.distance(plane, eye: eye)
      case .triangle(let triangle):
        LengthScale.edgeAndReach(triangle, eye: eye).reach
      case .ellipsoid(let ellipsoid): ellipsoid.reach(from: eye)
      }
    }
  }

  /// 2^k as a Double (k within Double's exponent range).
  @usableFromInline
  package static func factor(_ exponent: Int) -> Double {
    Double(sign: .plus, exponent: exponent, significand: 1)
  }
}

extension Primitives<Double> {
  /// Calls `body` with every primitive, kind by kind.
  func forEach(_ body: (LengthScale.Primitive) -> Void) {
    for kind in PrimitiveKind.allCases {
      switch kind {
      case .sphere: for sphere in spheres { body(.sphere(sphere)) }
      case .plane: for plane in planes { body(.plane(plane)) }
      case .triangle: for triangle in triangles { body(.triangle(triangle)) }
      case .ellipsoid:
        for ellipsoid in transformedSpheres { body(.ellipsoid(ellipsoid)) }
      case .shape:
        // Tested in the world's units, at no scale: no length to measure.
        break
      }
    }
  }
}

extension Sphere<Double> {
  /// Its largest length seen from `eye`: its centre's offset (max-norm)
  /// or its radius.
  func reach(from eye: Vector3<Double>) -> Double {
    Swift.max((center - eye).maxMagnitude, radius.magnitude)
  }
}

extension TransformedSphere<Double> {
  /// The length of its shortest axis, nearly: the sphere's radius times
  /// the shortest column of the matrix's linear part.
  package var shortestAxis: Double {
    let m = matrix
    // Each column's length without squaring it at its own scale, where
    // the squares of an axis of 1e-200 would underflow.
    func length(_ column: Vector3<Double>) -> Double {
      let largest = column.maxMagnitude
      return largest == 0 ? 0 : (column / largest).length * largest
    }
    return Swift.min(
      length(Vector3(m.m00, m.m10, m.m20)),
      length(Vector3(m.m01, m.m11, m.m21)),
      length(Vector3(m.m02, m.m12, m.m22))) * sphere.radius
  }

  /// Its largest length seen from `eye`: each linear entry of its matrix
  /// times the sphere's reach in its own space, and the translation's
  /// offset from the eye.
  func reach(from eye: Vector3<Double>) -> Double {
    let m = matrix
    let reach = sphere.center.maxMagnitude + sphere.radius
    var largest = Swift.max(
      (m.m03 - eye.x).magnitude, (m.m13 - eye.y).magnitude,
      (m.m23 - eye.z).magnitude)
    for entry in [
      m.m00, m.m01, m.m02, m.m10, m.m11, m.m12, m.m20, m.m21, m.m22,
    ] {
      largest = Swift.max(largest, entry.magnitude * reach)
    }
    return largest
  }
}

extension Primitives {
  /// Every length times `factor`, a power of two (see `LengthScale`).
  @usableFromInline
  package func scaled(by factor: Scalar) -> Primitives {
    var result = Primitives()
    for kind in PrimitiveKind.allCases {
      switch kind {
      case .sphere: result.spheres = spheres.map { $0.scaled(by: factor) }
      case .plane: result.planes = planes.map { $0.scaled(by: factor) }
      case .triangle:
        result.triangles = triangles.mapParts { $0.scaled(by: factor) }
      case .ellipsoid:
        result.transformedSpheres = transformedSpheres.map {
          TransformedSphere(
            sphere: $0.sphere, matrix: $0.matrix.rowsScaled(by: factor),
            inverse: $0.inverse.columnsScaled(by: 1 / factor))
        }
      case .shape:
        // Kept in the world's units: the fast engine tests them with the
        // world's ray (`CompiledScene.testShapes`).
        result.shapes = shapes
      }
    }
    return result
  }
}

extension Sphere {
  func scaled(by factor: Scalar) -> Sphere {
    Sphere(
      center: center * factor, radius: radius * factor,
      materialIndex: materialIndex)
  }
}

extension Plane {
  func scaled(by factor: Scalar) -> Plane {
    var plane = self
    plane.offset = offset * factor
    return plane
  }
}

extension Triangle {
  func scaled(by factor: Scalar) -> Triangle {
    var triangle = self
    triangle.v0 = v0 * factor
    triangle.v1 = v1 * factor
    triangle.v2 = v2 * factor
    return triangle
  }
}
