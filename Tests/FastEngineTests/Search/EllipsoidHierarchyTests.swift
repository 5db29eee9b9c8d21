import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The ellipsoids' own hierarchy (`buildEllipsoidHierarchy`): the same
/// nearest hit, t and ellipsoid, as testing each in order, for rays through
/// their rims (each moved by up to 64 ulps) and rays at random, at aspects
/// up to 10⁶, far from the eye and near it, coincident twins among them;
/// and each ellipsoid's answer the same whatever bound it is asked with.
final class EllipsoidHierarchyTests: XCTestCase {
  /// A scene of `count` ellipsoids: random rotations, scales of aspect up
  /// to 10⁶, sizes and distances over many binades; and the world points
  /// on their rims, as seen from the eye, to aim rays at.
  func randomScene(_ generator: inout SplitMix64, count: Int)
    -> (scene: Scene, rims: [Vector3<Double>])?
  {
    let size: Double = generator.logUniform(1e-3, 1e3)
    let eye = generator.unitVector(Double.self) * generator.logUniform(1, 1e6)
    var objects: [SceneObject<Double>] = []
    var rims: [Vector3<Double>] = []
    for index in 0..<count {
      if index % 7 == 6, case .transform(var twin) = objects.last {
        if case .sphere(var sphere) = twin.object {
          sphere.materialIndex = 1 - sphere.materialIndex
          twin.object = .sphere(sphere)
        }
        objects.append(.transform(twin))
        continue
      }
      // Half of them mild (aspect at most 4), tested in the sphere's space
      // in Float when the eye is within 64 radii.
      let aspect: Double =
        Bool.random(using: &generator)
        ? generator.logUniform(1, 4) : generator.logUniform(1, 1e6)
      let scale = Matrix4<Double>.scale(
        Vector3(1, generator.uniform(0.3...1), 1 / aspect))
      let turn =
        Matrix4<Double>.rotationX(degrees: generator.uniform(0...360))
        * .rotationY(degrees: generator.uniform(0...360))
        * .rotationZ(degrees: generator.uniform(0...360))
      let center =
        eye + generator.unitVector(Double.self)
        * (size * generator.logUniform(0.5, 100))
      let matrix = Matrix4<Double>.translation(center) * turn * scale
      let radius = size * generator.logUniform(0.05, 2)
      guard
        let transform = Transform(
          matrix: matrix,
          object: .sphere(
            Sphere(
              center: .zero, radius: radius,
              materialIndex: Int.random(in: 0...1, using: &generator))))
      else { return nil }
      objects.append(.transform(transform))
      // A point on the rim as seen from the eye: in the sphere's space the
      // eye is E', and points P with (P − E')·P = 0 on |P| = r lie on it.
      guard let inverse = matrix.inverse() else { return nil }
      let e = inverse.transformPoint(eye)
      let distance = e.length
      guard distance > radius else { continue }
      let along = radius * radius / distance
      let across =
        radius * (1 - (radius / distance) * (radius / distance)).squareRoot()
      for _ in 0..<5 {
        let side = e.cross(generator.unitVector(Double.self)).normalized()
        rims.append(
          matrix.transformPoint(e.normalized() * along + side * across))
      }
    }
    guard
      let camera = PerspectiveCamera<Double>(
        center: eye, direction: -eye, up: Vector3(0, 1, 0), angle: 60)
    else { return nil }
    return (
      Scene(
        camera: camera,
        lights: [
          .directional(direction: Vector3(-1, -2, -3), color: Vector3(1, 1, 1))
        ],
        materials: [
          Material(diffuse: Vector3(1, 0, 0)),
          Material(diffuse: Vector3(0, 1, 0)),
        ],
        root: Group(objects)),
      rims
    )
  }

  func check<Kernel: IntersectionKernel>(_: Kernel.Type, base: UInt64) {
    typealias S = Kernel.Scalar
    var tested = 0
    var hits = 0
    forEachSeed(Self.seedCount(40), base: base) { generator, _ in
      guard let (scene, rims) = randomScene(&generator, count: 24) else {
        return
      }
      let tree = CompiledScene<Kernel>(scene)
      XCTAssertNotNil(tree.ellipsoidHierarchy, "\(Kernel.self)")
      var each = tree
      each.ellipsoidHierarchy = nil
      each.wideEllipsoidHierarchy = nil
      let eye = scene.camera.center
      var targets = rims
      for _ in 0..<40 {
        targets.append(
          eye + generator.unitVector(Double.self)
            * generator.logUniform(1, 1e3))
      }
      for target in targets {
        let ulps = Double(S.ulpOfOne) * target.maxMagnitude
        let moved =
          target
          + Vector3(
            Double.random(in: -64...64, using: &generator),
            Double.random(in: -64...64, using: &generator),
            Double.random(in: -64...64, using: &generator)) * ulps
        let direction = Vector3<S>((moved - eye).normalized())
        let ray = CameraRay(origin: tree.rayOrigin, direction: direction)
        var found = NearestHit<S, CompiledScene<Kernel>.Nearest>(
          before: .infinity)
        tree.testEllipsoids(ray, &found)
        var expected = NearestHit<S, CompiledScene<Kernel>.Nearest>(
          before: .infinity)
        each.testEllipsoids(ray, &expected)
        tested += 1
        // Each ellipsoid's answer does not depend on the bound: asked up to
        // its own t it misses, up to t's successor it finds t again.
        for record in tree.ellipsoids {
          guard let t = Kernel.intersect(record, ray, before: .infinity)
          else { continue }
          XCTAssertNil(
            Kernel.intersect(record, ray, before: t), "\(Kernel.self)")
          XCTAssertEqual(
            Kernel.intersect(record, ray, before: t.nextUp), t,
            "\(Kernel.self)")
        }
        XCTAssertEqual(found.hit?.t, expected.hit?.t, "\(Kernel.self)")
        guard case .ellipsoid(let e)? = expected.hit?.what else {
          XCTAssertNil(found.hit, "\(Kernel.self)")
          continue
        }
        hits += 1
        guard case .ellipsoid(let f)? = found.hit?.what else {
          XCTFail("\(Kernel.self): the hierarchy lost ellipsoid \(e)")
          continue
        }
        XCTAssertEqual(f, e, "\(Kernel.self)")
      }
    }
    // Both kinds of answer, many times.
    XCTAssertGreaterThan(hits, tested / 10)
    XCTAssertLessThan(hits, tested)
  }

  func testSameAsEachInOrder_StableDouble() {
    check(StableKernel<Double>.self, base: 0xE11)
  }
  func testSameAsEachInOrder_StableFloat() {
    check(StableKernel<Float>.self, base: 0xE12)
  }
  func testSameAsEachInOrder_NaiveDouble() {
    check(NaiveKernel<Double>.self, base: 0xE13)
  }
  func testSameAsEachInOrder_NaiveFloat() {
    check(NaiveKernel<Float>.self, base: 0xE14)
  }
}
