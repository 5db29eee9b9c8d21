import Geometry
import SceneDescription
import PlatformSupport

/// The frame the records are computed in: the scene's values scaled by
/// 2^−k, or, where the eye is too far from the origin beside the scene's
/// lengths seen from it, moved to the eye first (see `LengthScale`).
extension LengthScale {
  /// `unscaled` and `eye` as the records of a render in `S` are computed
  /// from at the scale 2^−`exponent`: themselves at k = 0, which is every
  /// scene whose lengths seen from the eye are within 2^±(E/4) of 1;
  /// every value times 2^−k (`scaled`, exact) while the scaled
  /// coordinates stay within 2^(E/4), as they do for every scene whose eye
  /// is no farther from the origin than its lengths reach; else the scene
  /// moved to the eye first (`translated`), then scaled, with the eye at
  /// the origin.
  ///
  /// The exponent is judged from offsets from the eye (`exponent`), and
  /// the coordinates are not: an eye at 1e300 beside specks of 1e-300
  /// (double) is scaled by 2^997, which would take its coordinates to
  /// 10⁶⁰⁰. Moving first costs one rounding to Double of each offset,
  /// which is exact in that case (each coordinate is within R ≪ |eye| of
  /// the eye's, so x − eye is exact, Sterbenz) and otherwise within half
  /// an ulp of Double in the offset, below the record's own rounding.
  @usableFromInline
  package static func frame<S: RayScalar>(
    _ unscaled: consuming Primitives<Double>, eye: Vector3<Double>,
    exponent: Int, as _: S.Type
  ) -> (primitives: Primitives<Double>, eye: Vector3<Double>) {
    guard exponent != 0 else { return (unscaled, eye) }
    let factor = factor(-exponent)
    let coordinates = largestCoordinate(unscaled, eye: eye)
    guard coordinates > 0,
      Int(coordinates.exponent) - exponent > window(S.self)
    else {
      return (unscaled.scaled(by: factor), eye * factor)
    }
    return (unscaled.translated(by: eye).scaled(by: factor), .zero)
  }

  /// The largest magnitude of any value `scaled` multiplies: coordinates
  /// of the eye, centres and vertices, radii, plane offsets, the entries
  /// of a transformed sphere's matrix times its reach, its translation.
  static func largestCoordinate(
    _ all: Primitives<Double>, eye: Vector3<Double>
  ) -> Double {
    var largest = eye.maxMagnitude
    for kind in PrimitiveKind.allCases {
      switch kind {
      case .sphere:
        for sphere in all.spheres {
          largest = Swift.max(
            largest, sphere.center.maxMagnitude, sphere.radius.magnitude)
        }
      case .plane:
        for plane in all.planes {
          largest = Swift.max(largest, plane.offset.magnitude)
        }
      case .triangle:
        for mesh in all.triangles.parts {
          for vertex in mesh.vertices {
            largest = Swift.max(largest, vertex.maxMagnitude)
          }
        }
      case .ellipsoid:
        for ellipsoid in all.transformedSpheres {
          // Its reach from the origin: its offset from an eye there.
          largest = Swift.max(largest, ellipsoid.reach(from: .zero))
        }
      case .shape:
        // Not scaled: tested in the world's units.
        break
      }
    }
    return largest
  }
}

extension Primitives<Double> {
  /// The primitives seen from `eye`: every position minus the eye, each
  /// offset rounded once to Double (a plane's offset d − n·eye
  /// compensated, `CameraRelative.plane`); lengths, normals and shapes
  /// (tested in the world's units, with the world's ray) as they are.
  /// A transformed sphere's inverse gets M⁻¹ applied to the eye as its
  /// translation, as `transformPoint` computes it, so that the eye in its
  /// space (M⁻¹ applied to the origin now) is the same bits.
  func translated(by eye: Vector3<Double>) -> Primitives {
    var result = Primitives()
    for kind in PrimitiveKind.allCases {
      switch kind {
      case .sphere:
        result.spheres = spheres.map {
          Sphere(
            center: $0.center - eye, radius: $0.radius,
            materialIndex: $0.materialIndex)
        }
      case .plane:
        result.planes = planes.map {
          var plane = $0
          plane.offset = CameraRelative.plane(
            normal: $0.normal, offset: $0.offset, eye: eye)
          return plane
        }
      case .triangle:
        // Each vertex is 1·x + 0·y + 0·z − eye.x: x − eye.x rounded once;
        // the normals' cofactors of the identity are themselves.
        let move = Matrix4<Double>.translation(-eye)
        result.triangles = triangles.mapParts { $0.moved(by: move) }
      case .ellipsoid:
        result.transformedSpheres = transformedSpheres.map {
          TransformedSphere(
            sphere: $0.sphere, matrix: $0.matrix.movedBy(-eye),
            inverse: $0.inverse.applied(to: eye))
        }
      case .shape: result.shapes = shapes
      }
    }
    return result
  }
}

extension Matrix4<Double> {
  /// T(offset)·M: the first three rows plus offset times the last.
  fileprivate func movedBy(_ offset: Vector3<Double>) -> Matrix4 {
    var m = self
    m.m00 += offset.x * m30; m.m01 += offset.x * m31
    m.m02 += offset.x * m32; m.m03 += offset.x * m33
    m.m10 += offset.y * m30; m.m11 += offset.y * m31
    m.m12 += offset.y * m32; m.m13 += offset.y * m33
    m.m20 += offset.z * m30; m.m21 += offset.z * m31
    m.m22 += offset.z * m32; m.m23 += offset.z * m33
    return m
  }

  /// M·T(point): the last column M·(point, 1), in `transformPoint`'s
  /// order, so that this matrix applied to the origin is M applied to
  /// `point`, bit for bit.
  fileprivate func applied(to p: Vector3<Double>) -> Matrix4 {
    var m = self
    m.m03 = m00 * p.x + m01 * p.y + m02 * p.z + m03
    m.m13 = m10 * p.x + m11 * p.y + m12 * p.z + m13
    m.m23 = m20 * p.x + m21 * p.y + m22 * p.z + m23
    m.m33 = m30 * p.x + m31 * p.y + m32 * p.z + m33
    return m
  }
}
