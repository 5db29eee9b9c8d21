import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import Numerics
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

  // MARK: - Misses

  /// Rays parallel to the plane miss, above it or lying in it; a ray
  /// pointing away misses; zero and NaN directions miss without trapping.
  func checkParallelAndInvalid<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let rays: [(String, Ray<T>)] = [
      (
        "above, along x",
        Ray(origin: Vector3(-1, 0.25, 1), direction: Vector3(1, 0, 0))
      ),
      (
        "below, diagonal",
        Ray(origin: Vector3(-1, -1, -0.5), direction: Vector3(1, 1, 0))
      ),
      (
        "in the plane, along x",
        Ray(origin: Vector3(-1, 0.25, 0), direction: Vector3(1, 0, 0))
      ),
      (
        "in the plane, diagonal",
        Ray(origin: Vector3(-1, -1, 0), direction: Vector3(3, 2, 0))
      ),
      (
        "pointing away",
        Ray(origin: Vector3(0.25, 0.25, 1), direction: Vector3(0, 0, 1))
      ),
      ("zero direction", Ray(origin: Vector3(0.25, 0.25, 1), direction: .zero)),
      (
        "NaN direction",
        Ray(origin: Vector3(0.25, 0.25, 1), direction: Vector3(0, 0, T.nan))
      ),
      (
        "NaN origin",
        Ray(origin: Vector3(T.nan, 0.25, 1), direction: Vector3(0, 0, -1))
      ),
    ]
    for (name, ray) in rays {
      XCTAssertNil(kernel(ray, triangle), "\(T.self) \(name)")
      XCTAssertNil(
        triangle.intersect(ray, after: 0, before: .infinity),
        "\(T.self) \(name)")
    }
  }

  func testIntersect_ParallelAndInvalid_Float() {
    checkParallelAndInvalid(Float.self)
  }
  func testIntersect_ParallelAndInvalid_Double() {
    checkParallelAndInvalid(Double.self)
  }

  /// The back face is hit, with the normal of the winding (+z), not turned
  /// towards the ray; reversing the winding reverses the normal.
  func checkBackFace<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let fromBelow = Ray<T>(
      origin: Vector3(0.25, 0.25, -3), direction: Vector3(0, 0, 1))
    let hit = triangle.intersect(fromBelow, after: 0, before: .infinity)
    XCTAssertEqual(hit?.t, 3, "\(T.self)")
    XCTAssertEqual(
      hit?.normal, Vector3(0, 0, 1), "\(T.self): as wound, not flipped")
    let reversed = Triangle(triangle.v0, triangle.v2, triangle.v1)
    XCTAssertEqual(
      reversed.intersect(fromBelow, after: 0, before: .infinity)?.normal,
      Vector3(0, 0, -1), "\(T.self)")
  }

  func testIntersect_BackFace_Float() { checkBackFace(Float.self) }
  func testIntersect_BackFace_Double() { checkBackFace(Double.self) }

  /// Zero-area triangles miss, however the ray meets them: all three
  /// vertices equal, a repeated vertex, and exactly collinear vertices,
  /// along and across the segment they span.
  func checkDegenerate<T: RayScalar>(_: T.Type) {
    let cases: [(String, Triangle<T>)] = [
      (
        "one point",
        Triangle(Vector3(1, 1, 0), Vector3(1, 1, 0), Vector3(1, 1, 0))
      ),
      (
        "repeated vertex",
        Triangle(Vector3(0, 0, 0), Vector3(0, 0, 0), Vector3(2, 2, 0))
      ),
      (
        "repeated last vertex",
        Triangle(Vector3(0, 0, 0), Vector3(2, 2, 0), Vector3(2, 2, 0))
      ),
      (
        "collinear",
        Triangle(Vector3(0, 0, 0), Vector3(1, 1, 0), Vector3(2, 2, 0))
      ),
      (
        "collinear, oblique",
        Triangle(Vector3(0, 0, 0), Vector3(1, 2, 3), Vector3(4, 8, 12))
      ),
    ]
    for (name, triangle) in cases {
      XCTAssertTrue(triangle.isDegenerate, "\(T.self) \(name)")
      XCTAssertNil(triangle.geometricNormal, "\(T.self) \(name)")
      // Through the middle of the segment, and through an endpoint, from
      // several directions.
      let middle = (triangle.v0 + triangle.v2) * 0.5
      for target in [middle, triangle.v0, triangle.v2] {
        for direction in [
          Vector3<T>(0, 0, -1), Vector3(0.5, -0.25, -1), Vector3(-1, 0.5, 0.25),
        ] {
          let ray = Ray(origin: target - direction * 2, direction: direction)
          XCTAssertNil(
            triangle.intersect(ray, after: 0, before: .infinity),
            "\(T.self) \(name) at \(target) along \(direction)")
        }
      }
    }
    XCTAssertFalse(unitTriangle(T.self).isDegenerate)
    XCTAssertTrue(
      Triangle<T>(Vector3(0, 0, 0), Vector3(T.nan, 0, 0), Vector3(0, 1, 0))
        .isDegenerate)
  }

  func testIntersect_Degenerate_Float() { checkDegenerate(Float.self) }
  func testIntersect_Degenerate_Double() { checkDegenerate(Double.self) }

  /// Only tMin < t < tMax counts: a hit at exactly either end is excluded,
  /// one ulp inside is included, and a triangle behind the origin (t < 0)
  /// is missed with tMin = 0.
  func checkInterval<T: RayScalar>(_: T.Type) {
    let triangle = unitTriangle(T.self)
    let ray = Ray<T>(
      origin: Vector3(0.25, 0.25, 2), direction: Vector3(0, 0, -1))
    XCTAssertNil(triangle.intersect(ray, after: 0, before: 2), "t = tMax")
    XCTAssertEqual(triangle.intersect(ray, after: 0, before: T(2).nextUp)?.t, 2)
    XCTAssertNil(
      triangle.intersect(ray, after: 2, before: .infinity), "t = tMin")
    XCTAssertEqual(
      triangle.intersect(ray, after: T(2).nextDown, before: 3)?.t, 2)
    let behind = Ray<T>(
      origin: Vector3(0.25, 0.25, -2), direction: Vector3(0, 0, -1))
    XCTAssertNil(triangle.intersect(behind, after: 0, before: .infinity))
    XCTAssertEqual(
      triangle.intersect(behind, after: -.infinity, before: 0)?.t, -2,
      "the kernel finds it when the interval allows")
  }

  func testIntersect_Interval_Float() { checkInterval(Float.self) }
  func testIntersect_Interval_Double() { checkInterval(Double.self) }

  /// t is in multiples of the direction's length: scaling the direction by
  /// a power of two divides t exactly and leaves the barycentrics
  /// unchanged; by 3, t/3 within 2 ulps (the rounded 3·d and one more
  /// rounding of the result).
  func checkNonUnitDirections<T: RayScalar>(_: T.Type) {
    let triangle = Triangle<T>(
      Vector3(-1, -1, 5), Vector3(3, 0, 6), Vector3(0, 2, 4))
    let origin = Vector3<T>(0.1, 0.2, -0.3)
    let unit = (Vector3<T>(0.5, 0.4, 5) - origin).normalized()
    guard let reference = kernel(Ray(origin: origin, direction: unit), triangle)
    else {
      return XCTFail("\(T.self): the unit ray misses")
    }
    for scale: T in [4, 0.125, 1024] {
      let hit = kernel(Ray(origin: origin, direction: unit * scale), triangle)
      XCTAssertEqual(hit?.t, reference.t / scale, "\(T.self) × \(scale)")
      XCTAssertEqual(hit?.u, reference.u, "\(T.self) × \(scale)")
      XCTAssertEqual(hit?.w, reference.w, "\(T.self) × \(scale)")
    }
    let tripled = Ray(origin: origin, direction: unit * 3)
    guard let hit = kernel(tripled, triangle),
      let exact = referenceTriangleHit(tripled, triangle)
    else { return XCTFail("\(T.self): the tripled ray misses") }
    assertRelativeError(
      hit.t, exact.t, ulps: 8, "\(T.self): as the interior bound")
    assertRelativeError(
      hit.t * 3, ReferenceScalar(reference.t), ulps: 4,
      "\(T.self): 3·d rounds, t/3 rounds, and each t carries a few ulps")
  }

  func testIntersect_NonUnitDirections_Float() {
    checkNonUnitDirections(Float.self)
  }
  func testIntersect_NonUnitDirections_Double() {
    checkNonUnitDirections(Double.self)
  }

  // MARK: - Normals

  /// With vertex normals the hit's normal is their barycentric blend,
  /// normalised: the vertex's own normal at a vertex, the normalised mean
  /// at the centroid; normals that cancel fall back to the geometric one.
  func checkVertexNormals<T: RayScalar>(_: T.Type) {
    var triangle = unitTriangle(T.self)
    triangle.vertexNormals = .init(
      Vector3(0, 0, 2), Vector3(1, 0, 1), Vector3(0, 1, 1))
    let down = Vector3<T>(0, 0, -1)
    let atV0 = triangle.intersect(
      Ray(origin: Vector3(0, 0, 1), direction: down), after: 0,
      before: .infinity)
    XCTAssertEqual(atV0?.normal, Vector3(0, 0, 1), "\(T.self): n0 normalised")
    let atV1 = triangle.intersect(
      Ray(origin: Vector3(1, 0, 1), direction: down), after: 0,
      before: .infinity)
    assertRelativeError(
      atV1?.normal ?? .zero, Vector3<ReferenceScalar>(1, 0, 1).normalized(),
      ulps: 2, "\(T.self): a correctly rounded 1/√2, scaled")
    // At (0.25, 0.25): weights (0.5, 0.25, 0.25), blend (0.25, 0.25, 1.5).
    let inside = triangle.intersect(
      Ray(origin: Vector3(0.25, 0.25, 1), direction: down), after: 0,
      before: .infinity)
    assertRelativeError(
      inside?.normal ?? .zero,
      Vector3<ReferenceScalar>(0.25, 0.25, 1.5).normalized(),
      ulps: 3, "\(T.self): exact blend, then the normalisation's few ulps")

    triangle.vertexNormals = .init(
      Vector3(0, 0, 1), Vector3(0, 0, -1), Vector3(0, 0, 0))
    let cancelled = triangle.intersect(
      Ray(origin: Vector3(0.5, 0, 1), direction: down), after: 0,
      before: .infinity)
    XCTAssertEqual(
      cancelled?.normal, Vector3(0, 0, 1), "\(T.self): the geometric fallback")
  }

  func testIntersect_VertexNormals_Float() { checkVertexNormals(Float.self) }
  func testIntersect_VertexNormals_Double() { checkVertexNormals(Double.self) }

  /// The geometric normal of tiny and huge triangles, whose cross product
  /// would underflow or overflow unscaled.
  func checkNormalAtExtremeScales<T: RayScalar>(_: T.Type) {
    for exponent in [
      T.leastNormalMagnitude.exponent + 2,
      T.greatestFiniteMagnitude.exponent - 2,
    ] {
      let s = T(sign: .plus, exponent: exponent, significand: 1)
      let triangle = Triangle<T>(.zero, Vector3(s, 0, 0), Vector3(0, s, 0))
      XCTAssertEqual(
        triangle.geometricNormal, Vector3(0, 0, 1), "\(T.self) 2^\(exponent)")
    }
  }

  func testGeometricNormal_ExtremeScales_Float() {
    checkNormalAtExtremeScales(Float.self)
  }
  func testGeometricNormal_ExtremeScales_Double() {
    checkNormalAtExtremeScales(Double.self)
  }

  /// Conversion rounds each coordinate and keeps normals and material.
  func testConversion() {
    let third = 1.0 / 3
    let triangle = Triangle<Double>(
      Vector3(third, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0),
      vertexNormals: .init(
        Vector3(0, 0, 1), Vector3(0, 0.1, 1), Vector3(0, 0, 1)),
      materialIndex: 7)
    let converted = Triangle<Float>(triangle)
    XCTAssertEqual(converted.v0.x, Float(third))
    XCTAssertEqual(converted.vertexNormals?.n1.y, Float(0.1))
    XCTAssertEqual(converted.materialIndex, 7)
  }

  // MARK: - Watertightness

  /// A fan of 7 to 16 triangles around a shared centre, in a random plane
  /// and position; rays from random origins aimed exactly at the centre
  /// vertex or at points of the shared spokes must hit at least one
  /// triangle: the fan has no gap for a ray to leak through.
  func checkWatertightFan<T: RayScalar>(_: T.Type) {
    var leaksOfPlainTest = 0
    forEachSeed(300, base: 0x7121_0002) { generator, seed in
      let frame = randomFrame(using: &generator)
      let count = Int.random(in: 7...16, using: &generator)
      let centre = Vector3<T>(
        frame.point(
          generator.uniform(-0.1...0.1), generator.uniform(-0.1...0.1)))
      var ring: [Vector3<T>] = []
      for index in 0..<count {
        let angle =
          (Double(index) + generator.uniform(-0.3...0.3)) * 2 * .pi
          / Double(count)
        let radius: Double = generator.uniform(0.5...2)
        ring.append(
          Vector3<T>(frame.point(radius * cos(angle), radius * sin(angle))))
      }
      let triangles = (0..<count).map {
        Triangle(centre, ring[$0], ring[($0 + 1) % count])
      }
      for _ in 0..<20 {
        let spoke = ring[Int.random(in: 0..<count, using: &generator)]
        let s: Double =
          Bool.random(using: &generator) ? 0 : generator.uniform(0...0.9)
        let target =
          Vector3<Double>(centre)
          + (Vector3<Double>(spoke) - Vector3<Double>(centre)) * s
        leaksOfPlainTest += checkNoLeak(
          triangles, target: target, frame: frame, seed: seed, using: &generator
        )
      }
    }
    print(
      "\(T.self) fan: rays leaking through a plain Möller–Trumbore test: "
        + "\(leaksOfPlainTest)")
    XCTAssertGreaterThan(
      leaksOfPlainTest, 0,
      "\(T.self): the rays should find the gaps a non-watertight test leaves")
  }

  func testWatertight_Fan_Float() { checkWatertightFan(Float.self) }
  func testWatertight_Fan_Double() { checkWatertightFan(Double.self) }

  /// A 6×6 grid of jittered quads, each split along a random diagonal, in
  /// a random plane and position; rays aimed exactly at interior vertices
  /// and at points of interior edges must hit at least one triangle.
  func checkWatertightGrid<T: RayScalar>(_: T.Type) {
    var leaksOfPlainTest = 0
    let cells = 6
    forEachSeed(60, base: 0x7121_0003) { generator, seed in
      let frame = randomFrame(using: &generator)
      var grid: [[Vector3<T>]] = []
      for i in 0...cells {
        var row: [Vector3<T>] = []
        for j in 0...cells {
          let interior = i > 0 && i < cells && j > 0 && j < cells
          let jitter: Double = interior ? 0.3 : 0
          row.append(
            Vector3<T>(
              frame.point(
                (Double(i) + generator.uniform(-jitter...jitter))
                  / Double(cells) * 2 - 1,
                (Double(j) + generator.uniform(-jitter...jitter))
                  / Double(cells) * 2 - 1)))
        }
        grid.append(row)
      }
      var triangles: [Triangle<T>] = []
      // Edges shared by two triangles, as vertex pairs.
      var interiorEdges: [(Vector3<T>, Vector3<T>)] = []
      for i in 0..<cells {
        for j in 0..<cells {
          let a = grid[i][j]
          let b = grid[i + 1][j]
          let c = grid[i + 1][j + 1]
          let d = grid[i][j + 1]
          if Bool.random(using: &generator) {
            triangles += [Triangle(a, b, c), Triangle(a, c, d)]
            interiorEdges.append((a, c))
          } else {
            triangles += [Triangle(a, b, d), Triangle(b, c, d)]
            interiorEdges.append((b, d))
          }
          if i > 0 { interiorEdges.append((a, d)) }
          if j > 0 { interiorEdges.append((a, b)) }
        }
      }
      for _ in 0..<40 {
        let target: Vector3<Double>
        if Bool.random(using: &generator) {
          let i = Int.random(in: 1..<cells, using: &generator)
          let j = Int.random(in: 1..<cells, using: &generator)
          target = Vector3<Double>(grid[i][j])
        } else {
          let edge = interiorEdges[
            Int.random(in: 0..<interiorEdges.count, using: &generator)]
          let s: Double = generator.uniform(0...1)
          target =
            Vector3<Double>(edge.0)
            + (Vector3<Double>(edge.1) - Vector3<Double>(edge.0)) * s
        }
        leaksOfPlainTest += checkNoLeak(
          triangles, target: target, frame: frame, seed: seed, using: &generator
        )
      }
    }
    print(
      "\(T.self) grid: rays leaking through a plain Möller–Trumbore test: "
        + "\(leaksOfPlainTest)")
    XCTAssertGreaterThan(
      leaksOfPlainTest, 0,
      "\(T.self): the rays should find the gaps a non-watertight test leaves")
  }

  func testWatertight_Grid_Float() { checkWatertightGrid(Float.self) }
  func testWatertight_Grid_Double() { checkWatertightGrid(Double.self) }

  /// Casts one ray from a random origin (distance log-uniform in [0.5,
  /// 1000] mesh sizes, at least 0.05 in cosine from the plane, so that the
  /// rounding of the direction cannot carry the ray off the mesh) through
  /// `target`, and fails if no triangle is hit. Returns 1 when a plain
  /// Möller–Trumbore test in the same precision misses every triangle, to
  /// show that the rays probe the gaps such a test leaves.
  func checkNoLeak<T: RayScalar>(
    _ triangles: [Triangle<T>], target: Vector3<Double>, frame: Frame,
    seed: UInt64, using generator: inout SplitMix64
  ) -> Int {
    var direction = generator.unitVector(Double.self)
    while abs(direction.dot(frame.normal)) < 0.05 {
      direction = generator.unitVector(Double.self)
    }
    let distance: Double = generator.logUniform(0.5, 1000)
    let origin = Vector3<T>(target - direction * distance)
    let ray = Ray(origin: origin, direction: Vector3<T>(target) - origin)
    let prepared = WatertightRay(ray)
    let hits = triangles.filter {
      TriangleIntersection.intersect(
        prepared, $0.v0, $0.v1, $0.v2, after: 0, before: .infinity) != nil
    }
    XCTAssertFalse(
      hits.isEmpty,
      "\(T.self) seed \(seed): \(ray) leaks through the mesh at \(target)")
    return triangles.contains { mollerTrumbore(ray, $0) } ? 0 : 1
  }

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
