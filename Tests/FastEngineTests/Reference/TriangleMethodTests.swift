import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

final class TriangleMethodTests: XCTestCase {
  /// The unit right triangle in z = 0, wound counter-clockwise seen from +z,
  /// so its normal is +z.
  func unitTriangle<T: RayScalar>(_: T.Type = T.self) -> Triangle<T> {
    Triangle(
      Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), materialIndex: 3)
  }

  func kernel<T: RayScalar>(
    _ ray: Ray<T>, _ triangle: Triangle<T>, after tMin: T = 0,
    before tMax: T = .infinity
  ) -> (t: T, u: T, v: T, w: T)? {
    TriangleIntersection.intersect(
      WatertightRay(ray), triangle.v0, triangle.v1, triangle.v2,
      after: tMin, before: tMax)
  }

  // MARK: - Interior hits

  /// A ray straight down onto the interior: t, barycentrics, normal and
  /// material, all exact (small dyadic values).
  func checkInteriorExact<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let ray = Ray<T>(
      origin: Vector3(0.25, 0.5, 2), direction: Vector3(0, 0, -1))
    let hit = triangle.intersect(ray, after: 0, before: .infinity)
    XCTAssertEqual(hit?.t, 2, "\(T.self)")
    XCTAssertEqual(hit?.normal, Vector3(0, 0, 1), "\(T.self)")
    XCTAssertEqual(hit?.materialIndex, 3)
    let weights = kernel(ray, triangle)
    XCTAssertEqual(weights?.u, 0.25, "weight of v0: 1 − 0.25 − 0.5")
    XCTAssertEqual(weights?.v, 0.25, "weight of v1: x")
    XCTAssertEqual(weights?.w, 0.5, "weight of v2: y")
  }

  func testIntersect_InteriorExact_Float() { checkInteriorExact(Float.self) }
  func testIntersect_InteriorExact_Double() { checkInteriorExact(Double.self) }

  /// Random triangles (sizes log-uniform in [0.1, 10]) at random distances
  /// (log-uniform in [1, 1000] sizes) hit at random interior points (every
  /// barycentric ≥ 0.05) from directions at least 0.1 in cosine from the
  /// plane, of random lengths: t within 8 ulps of the Float80 intersection
  /// with the plane, and each barycentric within 4ε·(1 + κ) absolutely,
  /// κ = distance · longest edge / (2 · area · |cos θ|).
  ///
  /// Budgets: t = Σ wᵢzᵢ / Σ wᵢ with all weights ≥ 0 and all zᵢ of one
  /// sign, so nothing cancels and t collects the roundings of vᵢ − o, the
  /// shear's 1/d and product (3 per zᵢ), the 3-term sum and the division.
  /// Each sheared coordinate is within about 2ε·distance of exact, but the
  /// projected triangle is only as large as its edges, so each edge
  /// function (a 2D cross product) is off by about 2·2ε·distance·edge,
  /// against a total of twice the projected area, 2·area·|cos θ|: κ. The
  /// worst measured (about 4 ulps for t, 0.4 for the barycentrics) are
  /// printed.
  func checkInteriorRandom<T: RayScalar>(_: T.Type) {
    var worst = (t: 0.0, barycentric: 0.0)
    forEachSeed(2000, base: 0x7121_0001) { generator, seed in
      let size: Double = generator.logUniform(0.1, 10)
      let distance = size * generator.logUniform(1, 1000)
      let origin = Vector3<Double>(
        generator.uniform(-100...100), generator.uniform(-100...100),
        generator.uniform(-100...100))
      let centre = origin + generator.unitVector(Double.self) * distance
      let vertices = (0..<3).map { _ in
        Vector3<T>(centre + generator.unitVector(Double.self) * size)
      }
      let triangle = Triangle(vertices[0], vertices[1], vertices[2])
      guard let normal = triangle.geometricNormal else { return }
      var weights = (0..<3).map { _ in
        generator.uniform(0.05...1, as: Double.self)
      }
      let total = weights.reduce(0, +)
      weights = weights.map { $0 / total }
      let target =
        Vector3<Double>(vertices[0]) * weights[0]
        + Vector3<Double>(vertices[1]) * weights[1]
        + Vector3<Double>(vertices[2]) * weights[2]
      let ray = Ray<T>(
        origin: Vector3<T>(origin),
        direction: Vector3<T>(target - origin) * generator.logUniform(0.01, 100)
      )
      let cosine = Vector3<Double>(normal).dot(
        Vector3<Double>(ray.direction).normalized())
      guard abs(cosine) >= 0.1 else { return }
      guard let reference = referenceTriangleHit(ray, triangle),
        reference.weights.allSatisfy({ $0 > 0.01 })
      else {
        return XCTFail("\(T.self) seed \(seed): the reference misses")
      }
      guard let hit = kernel(ray, triangle) else {
        return XCTFail("\(T.self) seed \(seed): interior hit missed")
      }
      worst.t = max(
        worst.t,
        assertRelativeError(
          hit.t, reference.t, ulps: 8,
          "\(T.self) seed \(seed): no cancellation in Σwᵢzᵢ"))
      let edges = [
        vertices[1] - vertices[0], vertices[2] - vertices[1],
        vertices[0] - vertices[2],
      ].map { Vector3<Double>($0) }
      let area = edges[0].cross(edges[2]).length / 2
      let longest = edges.map(\.length).max() ?? 0
      let reach = (Vector3<Double>(vertices[0]) - origin).length
      let condition = reach * longest / (2 * area * abs(cosine))
      let scale = Double(T.ulpOfOne) * (1 + condition)
      for (got, want) in zip([hit.u, hit.v, hit.w], reference.weights) {
        let error = Double((ReferenceScalar(got) - want).magnitude) / scale
        worst.barycentric = max(worst.barycentric, error)
        XCTAssertLessThanOrEqual(
          error, 4,
          "\(T.self) seed \(seed): barycentric \(got) vs \(want), in units of "
            + "ε·(1 + κ), κ = \(condition)")
      }
    }
    print("\(T.self) worst interior errors: \(worst)")
  }

  func testIntersect_InteriorRandom_Float() { checkInteriorRandom(Float.self) }
  func testIntersect_InteriorRandom_Double() {
    checkInteriorRandom(Double.self)
  }

  // MARK: - Edges, vertices and just outside

  /// A ray through an edge or a vertex hits (the watertight convention:
  /// an edge function of exactly 0 is inside), straight and oblique; the
  /// barycentric of the opposite vertex is exactly 0. Dyadic values keep
  /// every step exact.
  func checkEdgesAndVertices<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let down = Vector3<T>(0, 0, -1)
    let oblique = Vector3<T>(0.25, 0.5, -1)
    let targets: [(String, Vector3<T>)] = [
      ("edge v0v1", Vector3(0.5, 0, 0)), ("edge v1v2", Vector3(0.5, 0.5, 0)),
      ("edge v2v0", Vector3(0, 0.75, 0)), ("vertex v0", Vector3(0, 0, 0)),
      ("vertex v1", Vector3(1, 0, 0)), ("vertex v2", Vector3(0, 1, 0)),
    ]
    for (name, target) in targets {
      for direction in [down, oblique, -down, -oblique] {
        let ray = Ray(origin: target - direction, direction: direction)
        let hit = kernel(ray, triangle)
        XCTAssertEqual(hit?.t, 1, "\(T.self) \(name) along \(direction)")
        let point = hit.map {
          triangle.v0 * $0.u + triangle.v1 * $0.v + triangle.v2 * $0.w
        }
        XCTAssertEqual(point, target, "\(T.self) \(name) along \(direction)")
      }
    }
  }

  func testIntersect_EdgesAndVertices_Float() {
    checkEdgesAndVertices(Float.self)
  }
  func testIntersect_EdgesAndVertices_Double() {
    checkEdgesAndVertices(Double.self)
  }

  /// A ray one tiny step outside an edge misses, one step inside hits:
  /// the step is 2⁻²⁰ (exact, and far above the rounding of these dyadic
  /// coordinates, which is none) and ε itself.
  func checkJustOutside<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let down = Vector3<T>(0, 0, -1)
    for step in [T(sign: .plus, exponent: -20, significand: 1), T.ulpOfOne] {
      let cases: [(String, Vector3<T>, Vector3<T>)] = [
        ("edge v0v1", Vector3(0.5, -step, 1), Vector3(0.5, step, 1)),
        ("edge v2v0", Vector3(-step, 0.5, 1), Vector3(step, 0.5, 1)),
        ("vertex v0", Vector3(-step, -step, 1), Vector3(step, step, 1)),
        ("edge v1v2", Vector3(0.5 + step, 0.5, 1), Vector3(0.5 - step, 0.5, 1)),
      ]
      for (name, outside, inside) in cases {
        XCTAssertNil(
          kernel(Ray(origin: outside, direction: down), triangle),
          "\(T.self) outside \(name) by \(step)")
        XCTAssertNotNil(
          kernel(Ray(origin: inside, direction: down), triangle),
          "\(T.self) inside \(name) by \(step)")
      }
    }
  }

  func testIntersect_JustOutside_Float() { checkJustOutside(Float.self) }
  func testIntersect_JustOutside_Double() { checkJustOutside(Double.self) }

  // MARK: - Helpers

  /// An orthonormal frame at a random position (|p| ≤ 50) and orientation.
  struct Frame {
    var origin: Vector3<Double>
    var u: Vector3<Double>
    var v: Vector3<Double>
    var normal: Vector3<Double>

    func point(_ a: Double, _ b: Double) -> Vector3<Double> {
      origin + u * a + v * b
    }
  }

  func randomFrame(using generator: inout SplitMix64) -> Frame {
    let normal = generator.unitVector(Double.self)
    let helper =
      abs(normal.x) < 0.9 ? Vector3<Double>(1, 0, 0) : Vector3(0, 1, 0)
    let u = normal.cross(helper).normalized()
    let origin = Vector3<Double>(
      generator.uniform(-50...50), generator.uniform(-50...50),
      generator.uniform(-50...50))
    return Frame(origin: origin, u: u, v: normal.cross(u), normal: normal)
  }

  /// The textbook Möller–Trumbore test in T, two-sided, edges inclusive:
  /// not watertight, because each triangle computes its shared edge from
  /// its own edge vectors.
  func mollerTrumbore<T: RayScalar>(_ ray: Ray<T>, _ triangle: Triangle<T>)
    -> Bool
  {
    let e1 = triangle.v1 - triangle.v0
    let e2 = triangle.v2 - triangle.v0
    let p = ray.direction.cross(e2)
    let determinant = e1.dot(p)
    guard determinant != 0 else { return false }
    let inverse = 1 / determinant
    let s = ray.origin - triangle.v0
    let u = s.dot(p) * inverse
    guard u >= 0 && u <= 1 else { return false }
    let q = s.cross(e1)
    let v = ray.direction.dot(q) * inverse
    guard v >= 0 && u + v <= 1 else { return false }
    return e2.dot(q) * inverse > 0
  }
}

/// The intersection of a ray with a triangle's plane and its barycentrics
/// (weights of v0, v1, v2), in ReferenceScalar by Cramer's rule
/// (Möller–Trumbore's form), from the exact values of T's inputs; nil when
/// the ray is parallel to the plane. Not limited to the triangle: the
/// caller checks the weights. For Float inputs every difference and
/// product is exact in 64 bits, so only a few final roundings remain; for
/// Double inputs each step rounds at 2⁻⁶⁴, 2¹¹ times finer than Double.
struct ReferenceTriangleHit {
  var t: ReferenceScalar
  var weights: [ReferenceScalar]
}

func referenceTriangleHit<T: RayScalar>(
  _ ray: Ray<T>, _ triangle: Triangle<T>
) -> ReferenceTriangleHit? {
  let origin = ray.origin.reference
  let direction = ray.direction.reference
  let v0 = triangle.v0.reference
  let e1 = triangle.v1.reference - v0
  let e2 = triangle.v2.reference - v0
  let p = direction.cross(e2)
  let determinant = e1.dot(p)
  guard determinant != 0 else { return nil }
  let s = origin - v0
  let q = s.cross(e1)
  let weight1 = s.dot(p) / determinant
  let weight2 = direction.dot(q) / determinant
  let t = e2.dot(q) / determinant
  return ReferenceTriangleHit(
    t: t, weights: [1 - weight1 - weight2, weight1, weight2])
}
