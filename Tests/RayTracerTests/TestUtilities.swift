import XCTest

@testable import FastEngine
@testable import Measurement
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport

// Helpers shared by the unit tests: a seedable generator, log-uniform
// sampling, errors measured in ulps, and reference intersections computed in
// the widest precision the platform has.

// MARK: - Random numbers

extension RandomNumberGenerator {
  /// A value whose logarithm is uniform in [log low, log high]: every binade
  /// between the bounds is equally likely, so small and large scales are
  /// exercised alike.
  mutating func logUniform<T: RayScalar>(_ low: T, _ high: T) -> T {
    precondition(low > 0 && high >= low)
    let exponent = Double.random(
      in: Double.log(Double(low))...Double.log(Double(high)), using: &self)
    return Swift.min(Swift.max(T(Double.exp(exponent)), low), high)
  }

  /// A value uniform in `range`, drawn in Double and rounded to T.
  mutating func uniform<T: RayScalar>(
    _ range: ClosedRange<Double>, as _: T.Type = T.self
  ) -> T {
    T(Double.random(in: range, using: &self))
  }

  /// +1 or −1 with equal probability.
  mutating func sign<T: RayScalar>(_: T.Type = T.self) -> T {
    Bool.random(using: &self) ? 1 : -1
  }

  /// A direction uniform on the unit sphere (normalised Gaussian-free
  /// rejection sampling from the cube), rounded to T.
  mutating func unitVector<T: RayScalar>(_: T.Type = T.self) -> Vector3<T> {
    while true {
      let v = Vector3<Double>(
        .random(in: -1...1, using: &self), .random(in: -1...1, using: &self),
        .random(in: -1...1, using: &self))
      let squared = v.lengthSquared
      if squared > 1e-4 && squared <= 1 {
        return Vector3<T>(v / squared.squareRoot())
      }
    }
  }
}

extension XCTestCase {
  /// Runs `body` once per iteration, each with a generator seeded from the
  /// iteration's own seed so that any one case replays alone; stops at the
  /// first iteration that records a failure and prints its seed.
  func forEachSeed(
    _ iterations: Int, base: UInt64,
    file: StaticString = #filePath, line: UInt = #line,
    _ body: (inout SplitMix64, UInt64) throws -> Void
  ) rethrows {
    for iteration in 0..<iterations {
      let seed = base &+ UInt64(iteration) &* 0x2545_F491_4F6C_DD1D
      var generator = SplitMix64(seed: seed)
      let failuresBefore = testRun?.totalFailureCount ?? 0
      try body(&generator, seed)
      if (testRun?.totalFailureCount ?? 0) > failuresBefore {
        let message =
          "iteration \(iteration) failed; replay with "
          + "SplitMix64(seed: 0x\(String(seed, radix: 16)))"
        print(message)
        XCTFail(message, file: file, line: line)
        return
      }
    }
  }
}

// MARK: - Errors in ulps

/// |got − want| / |want| in units of T.ulpOfOne, measured in
/// ReferenceScalar (so a correctly rounded result scores at most 0.5).
/// A zero `want` admits only a zero `got`; a non-finite `got` scores ∞.
func relativeErrorInUlps<T: RayScalar>(_ got: T, _ want: ReferenceScalar)
  -> Double
{
  guard got.isFinite else { return .infinity }
  if want == 0 { return got == 0 ? 0 : .infinity }
  let error = (ReferenceScalar(got) - want).magnitude / want.magnitude
  return Double(error / ReferenceScalar(T.ulpOfOne))
}

/// Asserts that `got` is within `ulps` units of T.ulpOfOne of `want`,
/// relatively; `reason` says why that budget (it is printed on failure).
@discardableResult
func assertRelativeError<T: RayScalar>(
  _ got: T, _ want: ReferenceScalar, ulps: Double, _ reason: String,
  file: StaticString = #filePath, line: UInt = #line
) -> Double {
  let measured = relativeErrorInUlps(got, want)
  XCTAssert(
    measured <= ulps,
    "\(T.self) \(got) vs \(want): relative error \(measured) ulps > \(ulps) "
      + "(\(reason))",
    file: file, line: line)
  return measured
}

/// The same, for each component of a vector against the largest component
/// of `want` (so that a component that should be zero is judged on the
/// vector's scale, as a direction's accuracy is).
@discardableResult
func assertRelativeError<T: RayScalar>(
  _ got: Vector3<T>, _ want: Vector3<ReferenceScalar>, ulps: Double,
  _ reason: String, file: StaticString = #filePath, line: UInt = #line
) -> Double {
  let measured = vectorErrorInUlps(got, want)
  XCTAssert(
    measured <= ulps,
    "\(T.self) \(got) vs \(want): error \(measured) ulps of the largest "
      + "component > \(ulps) (\(reason))",
    file: file, line: line)
  return measured
}

/// max |got_i − want_i| / max |want_i| in units of T.ulpOfOne.
func vectorErrorInUlps<T: RayScalar>(
  _ got: Vector3<T>, _ want: Vector3<ReferenceScalar>
) -> Double {
  guard got.isFinite else { return .infinity }
  let scale = want.maxMagnitude
  if scale == 0 { return got.maxMagnitude == 0 ? 0 : .infinity }
  let difference = (Vector3<ReferenceScalar>(got) - want).maxMagnitude
  return Double(difference / scale / ReferenceScalar(T.ulpOfOne))
}

// MARK: - Reference intersections

/// A hit computed in ReferenceScalar.
struct ReferenceHit {
  var t: ReferenceScalar
  var normal: Vector3<ReferenceScalar>
}

/// The nearest root in (tMin, tMax) of |o + t·d − centre| = r, from the exact
/// values of T's inputs, in ReferenceScalar, by the cancellation-free form
/// (closest approach l = p − (s/a)·d, q = s + sign(s)·√(a(r² − |l|²)),
/// roots q/a and c/q), written out here independently of the library.
///
/// Accurate to a few ReferenceScalar ulps of t (64 bits against Double's 53)
/// away from the silhouette, provided c = |p|² − r² (p = centre − o) is
/// accurate relative to itself: c carries an absolute error of about
/// 2^−64·|p|², which matters only when the origin is close to a huge
/// sphere. There c is exact for Float inputs (24-bit products are exact in
/// 64 bits) and for Double inputs whose coordinates and radius are integers
/// below 2^31, so the planet tests use such inputs.
///
/// The normal is (o + t·d − centre)/r, whose cancellation costs
/// 2^−64·|p|/r: negligible for Float below L/r = 10^6 and for Double below
/// L/r = 10^2, and meaningless beyond.
func referenceIntersect<T: RayScalar>(
  _ ray: Ray<T>, _ sphere: Sphere<T>, after tMin: T = 0,
  before tMax: T = .infinity
) -> ReferenceHit? {
  typealias R = ReferenceScalar
  let o = Vector3<R>(ray.origin)
  let d = Vector3<R>(ray.direction)
  let centre = Vector3<R>(sphere.center)
  let r = R(sphere.radius)
  let p = centre - o
  let a = d.lengthSquared
  let s = p.dot(d)
  let l = p - d * (s / a)
  let reduced = r * r - l.lengthSquared
  guard reduced >= 0 else { return nil }
  let root = (a * reduced).squareRoot()
  let q = s >= 0 ? s + root : s - root
  let c = p.lengthSquared - r * r
  let roots = [q / a, c / q].sorted()
  guard
    let t = roots.first(where: { $0 > R(tMin) && $0 < R(tMax) })
  else { return nil }
  let normal = (o + d * t - centre) / r
  return ReferenceHit(t: t, normal: normal)
}

/// t = (offset − n·o) / (n·d) for the plane's stored (already normalised)
/// normal and offset, in ReferenceScalar; nil when n·d = 0 or t is outside
/// (tMin, tMax). Exact but for the final roundings for Float inputs (24-bit
/// products are exact in 64 bits); for Double inputs each sum carries an
/// absolute error of about 2^−64 times its largest term.
func referenceIntersect<T: RayScalar>(
  _ ray: Ray<T>, _ plane: Plane<T>, after tMin: T = 0,
  before tMax: T = .infinity
) -> ReferenceHit? {
  typealias R = ReferenceScalar
  let n = Vector3<R>(plane.normal)
  let denominator = n.dot(Vector3<R>(ray.direction))
  guard denominator != 0 else { return nil }
  let t = (R(plane.offset) - n.dot(Vector3<R>(ray.origin))) / denominator
  guard t > R(tMin) && t < R(tMax) else { return nil }
  return ReferenceHit(t: t, normal: n)
}

// MARK: - Small conveniences

extension Vector3 {
  /// The vector in ReferenceScalar, exactly (every Float and Double is one).
  var reference: Vector3<ReferenceScalar> { Vector3<ReferenceScalar>(self) }
}

// MARK: - Scene errors

/// Asserts that `error` is one well-formed line whose position lies within
/// `bytes` (a column may point just past a line's end).
func assertWellFormed(
  _ error: SceneError, in bytes: [UInt8], seed: UInt64,
  file: StaticString = #filePath, line: UInt = #line
) {
  let description = error.description
  XCTAssertFalse(
    description.contains("\n"), "seed \(seed): more than one line", file: file,
    line: line)
  XCTAssertTrue(
    description.hasPrefix(
      "\(error.file):\(error.line):\(error.column): error: "),
    "seed \(seed): malformed description \(description.debugDescription)",
    file: file, line: line)
  let lines = bytes.split(
    separator: UInt8(ascii: "\n"), omittingEmptySubsequences: false)
  XCTAssertTrue(
    (1...lines.count).contains(error.line),
    "seed \(seed): line \(error.line) of \(lines.count)", file: file, line: line
  )
  if (1...lines.count).contains(error.line) {
    XCTAssertTrue(
      (1...(lines[error.line - 1].count + 1)).contains(error.column),
      "seed \(seed): column \(error.column) on line \(error.line)", file: file,
      line: line)
  }
}

/// The byte ranges of the blank-separated words of `bytes`, for the
/// mutation tests' edits.
func wordRanges(_ bytes: [UInt8]) -> [Range<Int>] {
  var ranges: [Range<Int>] = []
  var start: Int?
  for (index, byte) in bytes.enumerated() {
    let blank = byte == 0x20 || byte == 0x0A || byte == 0x09
    if blank, let begun = start {
      ranges.append(begun..<index)
      start = nil
    } else if !blank && start == nil {
      start = index
    }
  }
  if let begun = start { ranges.append(begun..<bytes.count) }
  return ranges
}

// MARK: - Renders

/// The number of pixels where two renders of one size differ in any
/// output, bit for bit.
func differences<S: RayScalar>(_ a: RenderBuffers<S>, _ b: RenderBuffers<S>)
  -> Int
{
  var count = 0
  for pixel in 0..<(a.width * a.height) {
    var same = true
    if !a.depth.isEmpty { same = same && a.depth[pixel] == b.depth[pixel] }
    if !a.normals.isEmpty {
      same = same && a.normals[pixel] == b.normals[pixel]
    }
    if !a.color.isEmpty { same = same && a.color[pixel] == b.color[pixel] }
    if !same { count += 1 }
  }
  return count
}

// MARK: - The project's files

enum ProjectFiles {
  /// Tests/RayTracerTests/TestUtilities.swift → the package.
  static var projectFolder: String {
    var parts = "\(#filePath)".split(
      separator: "/", omittingEmptySubsequences: false)
    parts.removeLast(3)
    return parts.joined(separator: "/")
  }

  /// Every scene of `scenes/` (both formats) and `scenes/stiff/`.
  static func projectScenes() throws -> [String] {
    var paths: [String] = []
    for folder in ["scenes", "scenes/stiff"] {
      let path = "\(projectFolder)/\(folder)"
      for name in try listFolder(path).sorted()
      where name.hasSuffix(".txt") || name.hasSuffix(".plist") {
        paths.append("\(path)/\(name)")
      }
    }
    return paths
  }
}

// MARK: - Long cases

/// Whether the long cases run (RAYTRACE_LONG_TESTS set; `.ci/run` sets
/// it).
let runsLongTests =
  ProcessInfo.processInfo.environment["RAYTRACE_LONG_TESTS"] != nil

extension XCTestCase {
  /// How many of a slow randomized test's `iterations` seeds run (as
  /// `forEachSeed(Self.seedCount(n), …)`): all of them with
  /// RAYTRACE_LONG_TESTS (CI), a quarter otherwise, so that a student's
  /// `swift test` in the unoptimised debug build stays within a minute.
  /// The seeds run are the first of the same sequence, so a failure found
  /// either way replays the same.
  static func seedCount(_ iterations: Int) -> Int {
    runsLongTests ? iterations : max(1, (iterations + 3) / 4)
  }

  /// Of a slow test's `cases`, all with RAYTRACE_LONG_TESTS (CI), every
  /// other one otherwise, starting at `half` (0 or 1), so that a student's
  /// `swift test` runs each kind of case once in one of two calls that take
  /// halves 0 and 1.
  static func quickCases<C: Collection>(_ cases: C, half: Int = 0)
    -> [C.Element]
  {
    runsLongTests
      ? Array(cases)
      : cases.enumerated().filter { $0.offset % 2 == half }.map(\.element)
  }

  /// Skips a case that takes seconds (exhaustive sweeps, every stiff scene
  /// against the double-double reference) unless RAYTRACE_LONG_TESTS is
  /// set, so that `swift test` stays within a minute on two cores; `.ci/run`
  /// sets it, so CI runs every case.
  func skipUnlessLongTests() throws {
    try XCTSkipUnless(
      runsLongTests, "a long case: RAYTRACE_LONG_TESTS=1 swift test runs it")
  }
}

/// `camera` as `style` builds its rays (`RenderSettings.camera`).
func styled<S: RayScalar>(_ camera: PerspectiveCamera<S>, _ style: ImageStyle)
  -> PerspectiveCamera<S>
{
  RenderSettings(width: 1, height: 1, outputs: [], style: style).camera(camera)
}

extension OBJMesh {
  /// Every face as a model triangle in precision S (`triangle(at:)`).
  func makeTriangles<S: RayScalar>(
    materialIndex: Int, as _: S.Type = S.self
  ) -> [Triangle<S>] {
    (0..<triangleCount).map {
      triangle(at: $0, materialIndex: materialIndex, as: S.self)
    }
  }

  /// The model triangle of `triangles[index]` in precision S, with vertex
  /// normals and texture coordinates where the face gave them, for callers
  /// that store each one straight into their own array. A degenerate
  /// triangle (a repeated vertex, a zero-area face) is made as any other:
  /// it is never hit, and dropping it is the compiled scene's choice.
  ///
  /// - Precondition: `0 <= index < triangleCount`.
  func triangle<S: RayScalar>(
    at index: Int, materialIndex: Int, as _: S.Type = S.self
  ) -> Triangle<S> {
    let face = face(index)
    let v = face.vertexIndices
    let normals = face.normalIndices.map { n in
      Triangle<S>.VertexNormals(
        Vector3<S>(self.normals[Int(n.x)]),
        Vector3<S>(self.normals[Int(n.y)]),
        Vector3<S>(self.normals[Int(n.z)]))
    }
    let coordinates = face.textureIndices.map { t in
      Triangle<S>.TextureCoordinates(
        TextureCoordinate<S>(textureCoordinates[Int(t.x)]),
        TextureCoordinate<S>(textureCoordinates[Int(t.y)]),
        TextureCoordinate<S>(textureCoordinates[Int(t.z)]))
    }
    return Triangle<S>(
      Vector3<S>(vertices[Int(v.x)]), Vector3<S>(vertices[Int(v.y)]),
      Vector3<S>(vertices[Int(v.z)]), vertexNormals: normals,
      textureCoordinates: coordinates, materialIndex: materialIndex)
  }
}

extension RenderBuffers<Double> {
  /// Every value's bits and every byte, output by output: equal for two
  /// renders only if they are the same bit for bit.
  var bits: [[UInt64]] {
    [
      depth.map(\.bitPattern),
      normals.flatMap { [$0.x, $0.y, $0.z] }.map(\.bitPattern),
      color.flatMap { [$0.x, $0.y, $0.z] }.map(\.bitPattern),
      normalBytes.map(UInt64.init),
      colorBytes.map(UInt64.init),
    ]
  }
}
