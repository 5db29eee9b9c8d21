import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Pipeline
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// One ellipsoid scene of the accuracy tests: a unit sphere placed by a
/// Transform's operations, seen by a camera, written in the text format.
struct EllipsoidCase: CustomStringConvertible {
  var name: String
  /// The Transform's operations, in the file's order.
  var operations: [String]
  var eye: (Double, Double, Double)
  var direction: (Double, Double, Double)
  var up: (Double, Double, Double) = (0, 1, 0)
  var angle: Double = 40

  var description: String { name }

  var text: String {
    func v(_ x: (Double, Double, Double)) -> String { "\(x.0) \(x.1) \(x.2)" }
    return """
      PerspectiveCamera { center \(v(eye)) direction \(v(direction))
        up \(v(up)) angle \(angle) }
      Lights { numLights 1 DirectionalLight { direction 0 0 -1 color 1 1 1 } }
      Background { color 0 0 0 ambientLight 0.1 0.1 0.1 }
      Materials { numMaterials 1 Material { diffuseColor 0.5 0.5 0.5 } }
      Group { numObjects 1 MaterialIndex 0
        Transform { \(operations.joined(separator: " "))
          Sphere { center 0 0 0 radius 1 } } }
      """
  }

  /// The ellipsoid's axes in the world, from the operations before the
  /// Scale (those that turn the scaled sphere), in Double: only the
  /// conditioning's perturbations use them, never the exact intersection.
  var axes: [Vector3<Double>] {
    var turn = Matrix4<Double>.identity
    for operation in operations {
      let words = operation.split(separator: " ")
      guard let angle = words.count == 2 ? Double(words[1]) : nil else {
        if words.first == "Scale" { break }
        continue
      }
      switch words[0] {
      case "XRotate": turn = turn * .rotationX(degrees: angle)
      case "YRotate": turn = turn * .rotationY(degrees: angle)
      case "ZRotate": turn = turn * .rotationZ(degrees: angle)
      default: break
      }
    }
    return [Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)].map {
      turn.transformDirection($0).normalized()
    }
  }

  func scene(_ precision: Precision) throws -> Scene {
    try SceneParser.parse(
      text, file: "\(name).txt",
      options: SceneOptions(
        style: .course, precision: precision.numberRange))
  }
}

/// How a fast-engine render of an `EllipsoidCase` compares with the exact
/// intersection (`ExactEllipsoid`) of the very same camera rays.
struct EllipsoidAccuracy: CustomStringConvertible {
  var pixels = 0
  /// Pixels the exact ellipsoid covers, and of them those off the rim.
  var exactHits = 0
  var interiorHits = 0
  /// Rim pixels: within `rimRoundings` roundings of the silhouette.
  var rim = 0
  /// Hit in one and not the other: off the rim, and on it.
  var disagreements = 0
  var rimDisagreements = 0
  /// The largest distance from the silhouette, in roundings
  /// (`rimDistance`/ε), of a pixel where they disagree.
  var farthestDisagreement = 0.0
  /// Off the rim: |t − t*| / (ε·t*·max(1, κ_t)), κ_t the relative change
  /// of t* per relative change of the ray's direction or of the
  /// ellipsoid's position (measured only where the error exceeds
  /// `conditionedFrom`·ε; elsewhere κ = 1).
  var tError = 0.0
  /// The same without the conditioning: |t − t*| / (ε·t*).
  var rawTError = 0.0
  /// Off the rim: the normal's angle / (ε·max(1, κ_n)), κ_n its angle's
  /// change per relative change of the direction or position.
  var normalError = 0.0
  var rawNormalError = 0.0
  /// Normals at more than 90° from the exact one, where both hit: off
  /// the rim, and on it (where the exact normal turns through 180° within
  /// the ray's rounding: the hit's t moves as the square root of it).
  var reversed = 0
  var rimReversed = 0

  /// Pixels within this many roundings of the silhouette (of the ray's
  /// direction or of the ellipsoid's position relative to the eye) are
  /// the rim, where hit or miss may go either way.
  static let rimRoundings = 4.0
  /// Errors above this many ε are checked against the pixel's
  /// conditioning.
  static let conditionedFrom = 4.0

  var description: String {
    "hits \(exactHits) (interior \(interiorHits), rim \(rim)), "
      + "disagreements \(disagreements) (rim \(rimDisagreements), "
      + "within \(format(farthestDisagreement)) roundings), "
      + "t \(format(tError)) ε (raw \(format(rawTError))), "
      + "normal \(format(normalError)) ε (raw \(format(rawNormalError))), "
      + "reversed \(reversed) (rim \(rimReversed))"
  }

  func format(_ x: Double) -> String {
    x < 100 ? String(format: "%.2f", x) : String(format: "%.3g", x)
  }

  /// Renders `test` (one ellipsoid) at `width`×`height` with
  /// `CompiledScene<StableKernel<R>>` and measures every pixel.
  static func measure<R: RayScalar>(
    _ test: EllipsoidCase, _: R.Type, width: Int, height: Int
  ) throws -> EllipsoidAccuracy {
    let scene = try test.scene(R.self == Float.self ? .float : .double)
    let axes = test.axes
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth, .normals])
    let buffers = Renderer.render(
      CompiledScene<StableKernel<R>>(scene), settings: settings)
    let placed = scene.root.flattened().transformedSpheres
    XCTAssertEqual(placed.count, 1, "one ellipsoid")
    guard let ellipsoid = placed.first else { return EllipsoidAccuracy() }
    let exact = ExactEllipsoid(
      matrix: ellipsoid.matrix, sphere: ellipsoid.sphere)
    let eye = scene.camera.center
    let epsilon = Double(R.ulpOfOne)
    // The camera rays exactly as `Renderer.renderRow` forms them.
    let camera = PerspectiveCamera<R>(scene.camera)
    let aspect = R(height) / R(width)
    var result = EllipsoidAccuracy()
    for row in 0..<height {
      let y: R = settings.screen.y(row: row)
      let rowBase = camera.rowBase(y: y, aspect: aspect)
      for column in 0..<width {
        let x: R = settings.screen.x(column: column)
        let direction = Vector3<Double>(
          camera.rayDirection(x: x, rowBase: rowBase))
        let pixel = row * width + column
        result.add(
          exact.intersect(eye: eye, direction: direction, axes: axes),
          t: Double(buffers.depth[pixel]),
          normal: Vector3<Double>(buffers.normals[pixel]), epsilon: epsilon,
          conditioning: {
            exact.conditioning(eye: eye, direction: direction, axes: axes)
          })
      }
    }
    return result
  }

  /// Rays from the eye aimed at the ellipsoid's equator (the image of
  /// the unit sphere's, M·(cos φ, sin φ, 0): its rim for a disc scaled
  /// last) from inside and outside, (1 ± 2⁻ᵏ) of the way out for k = 4 to
  /// 44, every 30° around, each measured as a pixel is: the pixels no
  /// camera grid puts on the rim.
  static func measureRim<R: RayScalar>(
    _ test: EllipsoidCase, _: R.Type
  ) throws -> EllipsoidAccuracy {
    let scene = try test.scene(R.self == Float.self ? .float : .double)
    let compiled = CompiledScene<StableKernel<R>>(scene)
    let placed = scene.root.flattened().transformedSpheres
    guard let ellipsoid = placed.first else { return EllipsoidAccuracy() }
    let exact = ExactEllipsoid(
      matrix: ellipsoid.matrix, sphere: ellipsoid.sphere)
    let (eye, axes) = (scene.camera.center, test.axes)
    var result = EllipsoidAccuracy()
    for degrees in stride(from: 0.0, to: 360, by: 30) {
      let angle = degrees * .pi / 180
      for k in stride(from: 4, through: 56, by: 2) {
        for side in [-1.0, 1.0] {
          let out = 1 + side * LengthScale.factor(-k)
          let target = ellipsoid.matrix.transformPoint(
            Vector3(cos(angle) * out, sin(angle) * out, 0))
          let direction = Vector3<R>((target - eye).normalized())
          let ray = CameraRay(origin: compiled.rayOrigin, direction: direction)
          let hit = compiled.nearest(ray)
          let wide = Vector3<Double>(direction)
          result.add(
            exact.intersect(eye: eye, direction: wide, axes: axes),
            t: hit.map { Double($0.t * compiled.lengthScale) } ?? .infinity,
            normal: hit.map {
              Vector3<Double>(compiled.normal(of: $0.what, ray, t: $0.t))
            } ?? .zero,
            epsilon: Double(R.ulpOfOne),
            conditioning: {
              exact.conditioning(eye: eye, direction: wide, axes: axes)
            })
        }
      }
    }
    return result
  }

  mutating func add(
    _ want: ExactEllipsoid.Result, t: Double, normal: Vector3<Double>,
    epsilon: Double,
    conditioning: () -> (t: Double, normal: Double)
  ) {
    pixels += 1
    let onRim = want.rimDistance <= Self.rimRoundings * epsilon
    if onRim { rim += 1 }
    if want.hit { exactHits += 1 }
    if want.hit && !onRim { interiorHits += 1 }
    let got = t.isFinite
    if got != want.hit {
      if onRim { rimDisagreements += 1 } else { disagreements += 1 }
      farthestDisagreement = Swift.max(
        farthestDisagreement, want.rimDistance / epsilon)
    }
    guard got, want.hit, let wantT = want.t, let wantNormal = want.normal
    else { return }
    let unit = Vector3<DoubleDouble>(normal) / Vector3<DoubleDouble>(normal)
      .length
    let cosine = unit.dot(wantNormal)
    if cosine < 0 {
      if onRim { rimReversed += 1 } else { reversed += 1 }
    }
    guard !onRim else { return }
    let tError = Double(
      ((DoubleDouble(t) - wantT) / wantT).magnitude.hi) / epsilon
    // The angle from |unit − want| = 2 sin(θ/2).
    let chord = Double((unit - wantNormal).length.hi)
    let angle = 2 * asin(Swift.min(chord / 2, 1))
    let normalError = angle / epsilon
    rawTError = Swift.max(rawTError, tError)
    rawNormalError = Swift.max(rawNormalError, normalError)
    var condition = (t: 1.0, normal: 1.0)
    if tError > Self.conditionedFrom || normalError > Self.conditionedFrom {
      let measured = conditioning()
      condition = (Swift.max(1, measured.t), Swift.max(1, measured.normal))
    }
    self.tError = Swift.max(self.tError, tError / condition.t)
    self.normalError = Swift.max(
      self.normalError, normalError / condition.normal)
  }
}

extension ExactEllipsoid {
  /// The relative change of t and the change of the normal's angle per
  /// relative change δ of the ray's direction (|δd| = δ·|d|, along each
  /// world axis) or of the eye's offset from the centre along each of the
  /// ellipsoid's `axes` (by δ times that offset's component: one rounding
  /// of the ellipsoid's position as its own frame holds it), the largest
  /// of the six, by exact intersections at δ = 2⁻³⁰: ∞ where a perturbed
  /// ray misses.
  func conditioning(
    eye: Vector3<Double>, direction: Vector3<Double>, axes: [Vector3<Double>]
  ) -> (t: Double, normal: Double) {
    let delta = 0x1p-30
    let base = intersect(eye: eye, direction: direction, axes: axes)
    guard let t = base.t, let normal = base.normal else {
      return (.infinity, .infinity)
    }
    let offset = offsetFromEye(eye)
    var worst = (t: 0.0, normal: 0.0)
    let world = [Vector3<Double>(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)]
    var moves = world.map { (eye, direction + $0 * (delta * direction.length)) }
    moves += axes.map { (eye - $0 * (delta * $0.dot(offset)), direction) }
    for (e, d) in moves {
      let moved = intersect(eye: e, direction: d, axes: axes)
      guard let movedT = moved.t, let movedNormal = moved.normal else {
        return (.infinity, .infinity)
      }
      let dt = Double(((movedT - t) / t).magnitude.hi) / delta
      let chord = Double((movedNormal - normal).length.hi)
      worst = (Swift.max(worst.t, dt), Swift.max(worst.normal, chord / delta))
    }
    return worst
  }

  /// C − E in Double.
  func offsetFromEye(_ eye: Vector3<Double>) -> Vector3<Double> {
    let e = [eye.x, eye.y, eye.z].map(ExactDyadic.init)
    let w = (0..<3).map {
      Double(ScaledDoubleDouble(center[$0] - e[$0]).value.hi)
    }
    return Vector3(w[0], w[1], w[2])
  }
}
