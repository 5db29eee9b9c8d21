import Foundation
import XCTest

import Geometry
import ExactArithmetic

// Helpers shared by the test targets: a seedable generator, log-uniform
// sampling, errors measured in ulps, the project's files and the long
// cases' switches.

// MARK: - Random numbers

extension RandomNumberGenerator {
  /// A value whose logarithm is uniform in [log low, log high]: every binade
  /// between the bounds is equally likely, so small and large scales are
  /// exercised alike.
  package mutating func logUniform<T: RayScalar>(_ low: T, _ high: T) -> T {
    precondition(low > 0 && high >= low)
    let exponent = Double.random(
      in: Double.log(Double(low))...Double.log(Double(high)), using: &self)
    return Swift.min(Swift.max(T(Double.exp(exponent)), low), high)
  }

  /// A value uniform in `range`, drawn in Double and rounded to T.
  package mutating func uniform<T: RayScalar>(
    _ range: ClosedRange<Double>, as _: T.Type = T.self
  ) -> T {
    T(Double.random(in: range, using: &self))
  }

  /// +1 or −1 with equal probability.
  package mutating func sign<T: RayScalar>(_: T.Type = T.self) -> T {
    Bool.random(using: &self) ? 1 : -1
  }

  /// A direction uniform on the unit sphere (normalised Gaussian-free
  /// rejection sampling from the cube), rounded to T.
  package mutating func unitVector<T: RayScalar>(_: T.Type = T.self) -> Vector3<
    T
  > {
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
  package func forEachSeed(
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
package func relativeErrorInUlps<T: RayScalar>(
  _ got: T, _ want: ReferenceScalar
)
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
package func assertRelativeError<T: RayScalar>(
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
package func assertRelativeError<T: RayScalar>(
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
package func vectorErrorInUlps<T: RayScalar>(
  _ got: Vector3<T>, _ want: Vector3<ReferenceScalar>
) -> Double {
  guard got.isFinite else { return .infinity }
  let scale = want.maxMagnitude
  if scale == 0 { return got.maxMagnitude == 0 ? 0 : .infinity }
  let difference = (Vector3<ReferenceScalar>(got) - want).maxMagnitude
  return Double(difference / scale / ReferenceScalar(T.ulpOfOne))
}

// MARK: - Small conveniences

extension Vector3 {
  /// The vector in ReferenceScalar, exactly (every Float and Double is one).
  package var reference: Vector3<ReferenceScalar> {
    Vector3<ReferenceScalar>(self)
  }
}

// MARK: - The project's files

package enum ProjectFiles {
  /// Tests/TestSupport/TestUtilities.swift → the package.
  package static var projectFolder: String {
    var parts = "\(#filePath)".split(
      separator: "/", omittingEmptySubsequences: false)
    parts.removeLast(3)
    return parts.joined(separator: "/")
  }

  /// Every scene of `scenes/` (both formats) and `scenes/stiff/`.
  package static func projectScenes() throws -> [String] {
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

  /// scenes/: the project's scenes.
  package static var scenesFolder: String { projectFolder + "/scenes" }

  /// scenes/stiff/: the stiff suite's scenes.
  package static var stiffFolder: String { projectFolder + "/scenes/stiff" }

  /// The stiff suite's scenes by name (`StiffSuiteTests`).
  package static let stiffScenes =
    [
      "far-sphere-1e2", "far-sphere-1e4", "far-sphere-1e6", "far-sphere-1e8",
      "planet-1e4", "planet-1e6", "planet-1e9", "grazing-sphere",
      "grazing-plane",
      "camera-inside-sphere", "sphere-behind-camera", "camera-on-plane",
      "parallel-plane", "translated-far", "scaled-small", "far-triangle-1e4",
      "ground-triangle", "grazing-triangle", "mesh-translated-1e6",
      "specks-and-planet-1e21", "specks-and-planet-1e201",
    ] + unitSphereScenes

  /// The stiff suite's unit spheres far from and near the origin.
  package static let unitSphereScenes = [10, 20, 30, 100, 200, 300].flatMap {
    ["unit-sphere-1e\($0)", "unit-sphere-1e-\($0)"]
  }
}

/// The names in `folder`.
package func listFolder(_ folder: String) throws -> [String] {
  try FileManager.default.contentsOfDirectory(atPath: folder)
}

// MARK: - Long cases

/// Whether the long cases run (RAYTRACE_LONG_TESTS set; `.ci/run` sets
/// it).
package let runsLongTests =
  ProcessInfo.processInfo.environment["RAYTRACE_LONG_TESTS"] != nil

extension XCTestCase {
  /// How many of a slow randomized test's `iterations` seeds run (as
  /// `forEachSeed(Self.seedCount(n), …)`): all of them with
  /// RAYTRACE_LONG_TESTS (CI), a quarter otherwise, so that a student's
  /// `swift test` in the unoptimised debug build stays within a minute.
  /// The seeds run are the first of the same sequence, so a failure found
  /// either way replays the same.
  package static func seedCount(_ iterations: Int) -> Int {
    runsLongTests ? iterations : max(1, (iterations + 3) / 4)
  }

  /// Of a slow test's `cases`, all with RAYTRACE_LONG_TESTS (CI), every
  /// other one otherwise, starting at `half` (0 or 1), so that a student's
  /// `swift test` runs each kind of case once in one of two calls that take
  /// halves 0 and 1.
  package static func quickCases<C: Collection>(_ cases: C, half: Int = 0)
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
  package func skipUnlessLongTests() throws {
    try XCTSkipUnless(
      runsLongTests, "a long case: RAYTRACE_LONG_TESTS=1 swift test runs it")
  }
}
