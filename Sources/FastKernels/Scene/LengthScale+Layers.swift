import Geometry
import SceneDescription
import PlatformSupport

/// Objects traced at their own scale: a scene whose objects span more than
/// the precision's squares hold at one common scale (a speck of 1e-20 by
/// the eye beside a planet 1e21 away, in Float) is split into layers, each
/// traced with its own power of two (see `LengthScale`).
extension LengthScale {
  /// A scene's primitives grouped by the scale each is traced at.
  @usableFromInline
  package struct Layers {
    /// What the scene's common scale 2^−`exponent` holds: every primitive
    /// whose squares and distances stay normal there (`tooSmall`). All of
    /// the scene for every scene the project had before, which therefore
    /// runs as before.
    @usableFromInline
    package var main: Primitives<Double>
    @usableFromInline
    package var exponent: Int
    /// The rest, grouped by their own scale (the k of a scene of the
    /// object alone with the same eye: from its lengths seen from the eye,
    /// `Primitive.reach`), largest first; scene order within each group.
    @usableFromInline
    package var others: [(primitives: Primitives<Double>, exponent: Int)]
  }

  /// `all` split into layers for a render in `S` seen from `eye`: one pass
  /// over the primitives for every scene whose objects all fit its common
  /// scale, a second only when one does not. A large mesh or group is
  /// measured by up to `threads` threads, with the same result.
  @usableFromInline
  package static func layers<S: RayScalar>(
    _ all: consuming Primitives<Double>, eye: Vector3<Double>,
    as _: S.Type, threads: Int = 1
  ) -> Layers {
    var extent = Extent(eye: eye, threads: threads)
    extent.add(all)
    let exponent = self.exponent(extent.largest, as: S.self)
    let scale = factor(-exponent)
    // The narrower of S's and Double's ranges, as for `exponent`: the
    // records are computed in Double first.
    let smallest = Swift.max(
      Double(S.leastNormalMagnitude), Double.leastNormalMagnitude)
    guard extent.fails(scale: scale, smallest: smallest) else {
      return Layers(main: all, exponent: exponent, others: [])
    }
    var main = Primitives<Double>()
    var others: [Int: Primitives<Double>] = [:]
    /// The scale the primitive is traced at: the scene's when it fits
    /// there, else its own.
    func layer(of primitive: Primitive) -> Int {
      guard
        tooSmall(primitive, eye: eye, scale: scale, smallest: smallest)
          != nil
      else { return exponent }
      return self.exponent(primitive.reach(from: eye), as: S.self)
    }
    func place(
      _ primitive: Primitive,
      _ append: (inout Primitives<Double>) -> Void
    ) {
      let k = layer(of: primitive)
      if k == exponent {
        append(&main)
      } else {
        append(&others[k, default: Primitives()])
      }
    }
    for kind in PrimitiveKind.allCases {
      switch kind {
      case .sphere:
        for sphere in all.spheres {
          place(.sphere(sphere)) { $0.spheres.append(sphere) }
        }
      case .plane:
        for plane in all.planes {
          place(.plane(plane)) { $0.planes.append(plane) }
        }
      case .triangle:
        for triangle in all.triangles {
          place(.triangle(triangle)) { $0.triangles.append(triangle) }
        }
      case .ellipsoid:
        for ellipsoid in all.transformedSpheres {
          place(.ellipsoid(ellipsoid)) {
            $0.transformedSpheres.append(ellipsoid)
          }
        }
      case .shape:
        // Tested in the world's units, whatever the scale.
        main.shapes = all.shapes
      }
    }
    return Layers(
      main: main, exponent: exponent,
      others: others.sorted { $0.key > $1.key }.map {
        (primitives: $0.value, exponent: $0.key)
      })
  }
}
