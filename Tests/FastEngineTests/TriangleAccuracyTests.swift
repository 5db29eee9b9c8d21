import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// The fast engine's t for triangles of every size and shape, against the
/// exact intersection of the very rays it traced (`exactTriangleT`: exact
/// dyadic arithmetic on the scene's Double vertices, the eye and the
/// ray's rounded direction, so the only error measured is the engine's).
///
/// The bounds (`bound(cosine:exactPlane:)`), in ulps of the exact t:
/// - t from the exact plane (large and thin triangles): 2 ulps for the
///   roundings of k and of the quotient (each half an ulp of a relative
///   error, up to an ulp once counted in ulps of t), plus, where n·d is
///   summed plainly (|n·d| ≥ ¼, so cos θ ≥ ¼), three roundings of terms
///   whose magnitudes sum to at most |n||d|: 3/cos θ ulps; below, n·d is
///   compensated and the bound is 3 ulps at any angle.
/// - the watertight test's t (every other triangle, whose estimated error
///   factor is below `TrianglePlane.conditionLimit`): 2 + 5/cos θ ulps,
///   measured at most 4.2/cos θ over random triangles of factor up to 16
///   (docs/ACCURACY.md, "Triangles"). The 1/cos θ is the exact t's own
///   sensitivity to a rounding of the ray's direction (tan θ ulps), so it
///   stays within the conditioning of each pixel.
/// Before the exact planes, the watertight t was 54–648 ulps off for large
/// triangles and up to 3.6·10¹⁰ ulps for slivers.
final class TriangleAccuracyTests: XCTestCase {
  typealias Vertices = (Vector3<Double>, Vector3<Double>, Vector3<Double>)

  /// ulps allowed for a ray meeting the triangle's plane at `cosine`, t
  /// from its exact plane or from the watertight test.
  static func bound(cosine: Double, exactPlane: Bool) -> Double {
    guard exactPlane else { return 2 + 5 / cosine }
    return cosine < 0.25 ? 3 : 2 + 3 / cosine
  }

  func sceneText(
    eye: Vector3<Double>, direction: Vector3<Double>, angle: Double,
    triangles: [Vertices]
  ) -> String {
    func v(_ p: Vector3<Double>) -> String { "\(p.x) \(p.y) \(p.z)" }
    var text = """
      PerspectiveCamera { center \(v(eye)) direction \(v(direction)) \
      up 0 1 0 angle \(angle) }
      Background { color 0 0 0 }
      Materials { numMaterials 1 PhongMaterial { diffuseColor 1 1 1 } }
      Group { numObjects \(triangles.count) MaterialIndex 0

      """
    for (a, b, c) in triangles {
      text += "Triangle { vertex0 \(v(a)) vertex1 \(v(b)) vertex2 \(v(c)) }\n"
    }
    return text + "}\n"
  }

  func scene(
    eye: Vector3<Double>, direction: Vector3<Double> = Vector3(0, 0, -1),
    angle: Double = 60, triangles: [Vertices]
  ) throws -> Scene {
    try SceneParser.parse(
      sceneText(
        eye: eye, direction: direction, angle: angle, triangles: triangles),
      file: "accuracy.txt")
  }

  struct Measured {
    var worst = 0.0
    var worstOverBound = 0.0
    var hits = 0
    var lost = 0
    /// Triangles whose t came from their exact planes.
    var planes = 0
  }

  /// Rays from the eye through `count` points inside each triangle (away
  /// from its edges by a tenth of the barycentric range, so the watertight
  /// decision is not in question), each compared with the exact t.
  func measureRays<S: RayScalar>(
    _ scene: Scene, triangles: [Vertices], as _: S.Type, count: Int = 64,
    hierarchyThreshold: Int = BoundingVolumeHierarchy<S>.defaultThreshold,
    exactPlane: Bool? = nil
  ) -> Measured {
    let compiled = CompiledScene<StableKernel<S>>(
      scene, hierarchyThreshold: hierarchyThreshold)
    let eye = scene.camera.center
    var generator = SplitMix64(seed: 7)
    var measured = Measured()
    measured.planes =
      compiled.exactPlanes.count + compiled.trianglePlanes.count
    for (a, b, c) in triangles {
      for _ in 0..<count {
        let r1 = 0.1 + 0.8 * Double(generator.next() % 1_000_001) / 1e6
        let r2 = 0.1 + 0.8 * Double(generator.next() % 1_000_001) / 1e6
        let (u, v) = r1 + r2 > 1 ? (1 - r1, 1 - r2) : (r1, r2)
        // The point is rounded, the direction too: the exact reference
        // takes the direction as the engine holds it.
        let point = a + (b - a) * u + (c - a) * v
        let direction = Vector3<S>((point - eye).normalized())
        let ray = CameraRay(origin: compiled.rayOrigin, direction: direction)
        let exactDirection = Vector3<Double>(direction)
        guard
          let exact = exactTriangleT(
            a, b, c, origin: eye, direction: exactDirection)
        else { continue }
        // A miss counts as lost only for rays the exact triangle holds
        // well inside: nearer its edges than a few ulps of the distance,
        // the watertight test decides on the rounded vertices and the
        // shear's roundings, and a hit there is checked all the same.
        // Distances from the edges as the ray sees them: the triangle
        // projected across the ray, its area shrunk by cos θ.
        let weights = exact.weights
        let cross = (b - a).cross(c - a)
        let twiceArea =
          cross.length * cross.normalized().dot(exactDirection).magnitude
          / exactDirection.length
        let margin = 64 * Double(S.ulpOfOne) * (point - eye).length
        let inside =
          weights.0 * twiceArea > margin * (c - b).length
          && weights.1 * twiceArea > margin * (a - c).length
          && weights.2 * twiceArea > margin * (b - a).length
        guard let hit = compiled.nearest(ray) else {
          if inside { measured.lost += 1 }
          continue
        }
        measured.hits += 1
        let t = Double(hit.t * compiled.lengthScale)
        let ulp = Double(S(exact.hi).ulp)
        let error = ((t - exact.hi) - exact.lo).magnitude / ulp
        let normal = (b - a).cross(c - a).normalized()
        let cosine =
          normal.dot(exactDirection).magnitude / exactDirection.length
        measured.worst = Swift.max(measured.worst, error)
        measured.worstOverBound = Swift.max(
          measured.worstOverBound,
          error
            / Self.bound(
              cosine: cosine, exactPlane: exactPlane ?? (measured.planes > 0)))
      }
    }
    return measured
  }

  /// `measureRays` through the flat loop and the hierarchy, within the
  /// exact plane's bound (or the watertight test's, for triangles that
  /// need no plane).
  func assertExact<S: RayScalar>(
    _ name: String, _ scene: Scene, _ triangles: [Vertices], as _: S.Type,
    exactPlane: Bool = true,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    for threshold in [1, BoundingVolumeHierarchy<S>.defaultThreshold] {
      let measured = measureRays(
        scene, triangles: triangles, as: S.self,
        hierarchyThreshold: threshold, exactPlane: exactPlane)
      XCTAssertEqual(
        measured.lost, 0, "\(name) \(S.self): rays lost", file: file, line: line
      )
      XCTAssertGreaterThan(measured.hits, 0, file: file, line: line)
      XCTAssertLessThanOrEqual(
        measured.worstOverBound, 1,
        "\(name) \(S.self): \(measured.worst) ulps", file: file, line: line)
      print(
        "TriangleAccuracy \(name) \(S.self) threshold \(threshold): worst "
          + "\(measured.worst) ulps, \(measured.worstOverBound) of the bound, "
          + "\(measured.planes) planes"
      )
    }
  }

  /// A ground triangle `across` times the eye's height across, seen from
  /// that height.
  func ground(_ across: Double) -> Vertices {
    let h = across / 2
    return (Vector3(-h, 0, h), Vector3(h, 0, h), Vector3(0, 0, -h))
  }

  func testGroundTriangles() throws {
    for across in [100.0, 1000.0, 2000.0, 1e6] {
      let triangle = ground(across)
      let s = try scene(
        eye: Vector3(0, 1, 0), direction: Vector3(0, -0.2, -1),
        triangles: [triangle])
      assertExact("ground \(across)", s, [triangle], as: Float.self)
      assertExact("ground \(across)", s, [triangle], as: Double.self)
    }
  }

  /// A triangle `across` units wide in a tilted plane one unit from the
  /// eye, its vertices rounded to Double (so not exactly on any simple
  /// plane).
  func tilted(_ across: Double, normal: Vector3<Double>) -> Vertices {
    let n = normal.normalized()
    let helper = abs(n.x) < 0.9 ? Vector3<Double>(1, 0, 0) : Vector3(0, 1, 0)
    let u = n.cross(helper).normalized()
    let v = n.cross(u)
    let centre = n * -1.0 + Vector3(0.1, -0.2, -0.3)
    let h = across / 2
    return (centre + u * h, centre - u * h + v * h, centre - v * (h * 0.9))
  }

  func testTiltedTriangles() throws {
    for across in [9.0, 900.0, 1e5] {
      for normal in [
        Vector3(0.2, 1, 0.1), Vector3(1, 2, 3), Vector3(-3, 1, 0.5),
      ] {
        // 9 across, one unit away: an error factor below 16, the
        // watertight test's t.
        let triangle = tilted(across, normal: normal)
        let s = try scene(eye: .zero, triangles: [triangle])
        assertExact(
          "tilted \(across) \(normal)", s, [triangle], as: Float.self,
          exactPlane: across > 9)
        assertExact(
          "tilted \(across) \(normal)", s, [triangle], as: Double.self,
          exactPlane: across > 9)
      }
    }
  }

  /// A sliver `length` long and `aspect`·`length` wide, 3 units in front
  /// of the eye, along `axis` (its width across it).
  func sliver(aspect: Double, along axis: Vector3<Double>, tilt: Double)
    -> Vertices
  {
    let a = axis.normalized()
    let across = a.cross(Vector3(tilt, 0.3, 1)).normalized()
    let centre = Vector3<Double>(0.05, -0.02, -3)
    return (
      centre - a, centre + a, centre + across * (2 * aspect) + a * 0.3
    )
  }

  func testSlivers() throws {
    for (aspect, precisions) in [
      (1e-4, 2), (1e-6, 2), (1e-8, 1), (1e-12, 1), (1e-15, 1),
    ] {
      for (axis, tilt) in [
        (Vector3<Double>(1, 0, 0), 0.0), (Vector3(1, 1, 0), 0.7),
        (Vector3(0.3, -1, 0.2), -2.0), (Vector3(1, 0.2, -0.9), 0.2),
      ] {
        let triangle = sliver(aspect: aspect, along: axis, tilt: tilt)
        let s = try scene(eye: Vector3(0.5, 0.25, 0.125), triangles: [triangle])
        if precisions > 1 {
          assertExact("sliver \(aspect) \(axis)", s, [triangle], as: Float.self)
        }
        assertExact("sliver \(aspect) \(axis)", s, [triangle], as: Double.self)
      }
    }
  }

  /// Triangles of every kind at random: 10^−0.5 to 10^1.5 from the eye,
  /// 10⁻² to 10 times that across, aspect 1 to 10⁻⁴ (and 10⁻¹² in double),
  /// in random orientations, each compiled alone (so the hierarchy, the
  /// flat loop and the large triangles' list each see some), eight rays
  /// each. Before the exact planes the worst was 10⁵ ulps·cos θ.
  func checkRandomTriangles<S: RayScalar>(
    _: S.Type, narrowest: Double,
    count: Int = TriangleAccuracyTests.seedCount(600)
  ) throws {
    var generator = SplitMix64(seed: 11)
    func uniform() -> Double {
      Double(generator.next() % 1_000_000_007) / 1_000_000_007
    }
    func direction() -> Vector3<Double> {
      Vector3(uniform() * 2 - 1, uniform() * 2 - 1, uniform() * 2 - 1)
        .normalized()
    }
    var worst = 0.0
    var worstOverBound = 0.0
    var hits = 0
    var planes = 0
    for index in 0..<count {
      let distance = pow(10, uniform() * 2 - 0.5)
      let size = distance * pow(10, uniform() * 3 - 2)
      let aspect = pow(10, log10(narrowest) * uniform())
      let eye = Vector3<Double>(0.25, -0.5, 2)
      let centre = eye + direction() * distance
      let axis = direction()
      let across = axis.cross(direction()).normalized()
      let triangle = (
        centre - axis * (size / 2), centre + axis * (size / 2),
        centre + axis * (size * (uniform() - 0.5)) + across * (size * aspect)
      )
      let camera = try XCTUnwrap(
        PerspectiveCamera<Double>(
          center: eye, direction: centre - eye, up: Vector3(0, 1, 0),
          angle: 60))
      let scene = Scene(
        camera: camera, materials: [.defaultWhite],
        root: Group([
          .triangle(Triangle(triangle.0, triangle.1, triangle.2))
        ]))
      let measured = measureRays(
        scene, triangles: [triangle], as: S.self, count: 8,
        hierarchyThreshold: index % 2 == 0 ? 1 : 12)
      XCTAssertEqual(measured.lost, 0, "triangle \(index) \(triangle)")
      worst = Swift.max(worst, measured.worst)
      worstOverBound = Swift.max(worstOverBound, measured.worstOverBound)
      hits += measured.hits
      planes += measured.planes
      if measured.worstOverBound > 1 {
        XCTFail("triangle \(index) \(triangle): \(measured.worst) ulps")
      }
    }
    XCTAssertGreaterThan(hits, count * 4)
    XCTAssertGreaterThan(planes, count / 10, "some take the exact plane")
    print(
      "TriangleAccuracy random \(S.self): worst \(worst) ulps, "
        + "\(worstOverBound) of the bound, \(planes) of \(count) planes"
    )
  }

  func testRandomTriangles_Float() throws {
    try checkRandomTriangles(Float.self, narrowest: 1e-4)
  }

  func testRandomTriangles_Double() throws {
    try checkRandomTriangles(Double.self, narrowest: 1e-12)
  }

  /// The render's own depth image, 64×48, against the exact t of each
  /// pixel's camera ray (made as `Renderer.renderRow` makes it) with the
  /// plane of `triangles` (coplanar, so one exact plane holds them all):
  /// the flat loop, the hierarchy and the screen tiles.
  func checkImage<S: RayScalar>(
    _ name: String, _ scene: Scene, plane triangle: Vertices, as _: S.Type,
    exactPlane: Bool = true,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    let (width, height) = (64, 48)
    let settings = RenderSettings(
      width: width, height: height, outputs: [.depth], threads: 1)
    let camera = PerspectiveCamera<S>(scene.camera)
    let aspect = S(height) / S(width)
    for (hierarchy, projection) in [
      (Int.max, Int.max), (1, Int.max), (Int.max, 1),
    ] {
      let compiled = CompiledScene<StableKernel<S>>(
        scene, hierarchyThreshold: hierarchy,
        triangleProjectionThreshold: projection)
      let depth = Renderer.render(compiled, settings: settings).depth
      var worst = 0.0
      var hits = 0
      for row in 0..<height {
        let y: S = settings.screen.y(row: row)
        let rowBase = camera.rowBase(y: y, aspect: aspect)
        for column in 0..<width {
          let x: S = settings.screen.x(column: column)
          let direction = Vector3<Double>(
            camera.rayDirection(x: x, rowBase: rowBase))
          let t = depth[row * width + column]
          guard t.isFinite,
            let exact = exactTriangleT(
              triangle.0, triangle.1, triangle.2, origin: scene.camera.center,
              direction: direction)
          else { continue }
          hits += 1
          let error =
            ((Double(t) - exact.hi) - exact.lo).magnitude
            / Double(S(exact.hi).ulp)
          let normal = (triangle.1 - triangle.0).cross(triangle.2 - triangle.0)
            .normalized()
          let cosine = normal.dot(direction).magnitude / direction.length
          worst = Swift.max(
            worst, error / Self.bound(cosine: cosine, exactPlane: exactPlane))
        }
      }
      XCTAssertGreaterThan(
        hits, width * height / 8, "\(name)", file: file, line: line)
      XCTAssertLessThanOrEqual(
        worst, 1, "\(name) \(S.self) \(hierarchy) \(projection)", file: file,
        line: line)
    }
  }

  /// The ground triangle `across` times the eye's height across (as the
  /// stiff suite's), cut into 16 (all in y = 0, so their plane is exact),
  /// seen from that height: the images of the first rows (the
  /// widest and in Float only, unless RAYTRACE_LONG_TESTS: each image is 18
  /// renders and 18,000 exact references in the unoptimised debug build).
  func testGroundImages() throws {
    for across in runsLongTests ? [100.0, 1000.0, 2000.0] : [2000.0] {
      var fan = [ground(across)]
      for _ in 0..<2 {
        fan = fan.flatMap { a, b, c -> [Vertices] in
          let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5)
          return [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        }
      }
      let s = try scene(
        eye: Vector3(0, 1, 0), direction: Vector3(0, -0.2, -1), triangles: fan)
      checkImage("ground \(across)", s, plane: fan[0], as: Float.self)
      if runsLongTests {
        checkImage("ground \(across)", s, plane: fan[0], as: Double.self)
      }
    }
  }
}
