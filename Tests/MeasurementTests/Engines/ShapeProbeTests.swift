import Course
import Measurement
import SceneIO
import Geometry
import SceneDescription
import XCTest

/// `--check`'s shape probes (`ShapeProbes`): the course's shapes and the
/// slide's formulas pass every probe, and each common mistake, written
/// into a shape of the test's own and handed in through the factories,
/// fails with its cause named.
final class ShapeProbeTests: XCTestCase {
  // MARK: - Running the probes

  /// The probes of one kind, with the factories changed by `change`.
  func probe(
    _ kind: ProbedKind, _ change: (inout ShapeFactories) -> Void
  ) -> ShapeProbeReport {
    var factories = ShapeFactories.course
    change(&factories)
    return ShapeProbes.probe([kind], factories: factories)
  }

  func causes(_ report: ShapeProbeReport) -> [ProbeCause] {
    report.diagnoses.map(\.cause)
  }

  /// The report fails, names `cause` first, and says so in a line that
  /// names the shape and contains `words`.
  func assertNames(
    _ report: ShapeProbeReport, _ cause: ProbeCause, first: Bool = true,
    _ words: String, file: StaticString = #filePath, line: UInt = #line
  ) {
    let lines = report.lines.joined(separator: "\n")
    XCTAssertFalse(report.passes, lines, file: file, line: line)
    let found =
      first
      ? report.diagnoses.first
      : report.diagnoses.first {
        $0.cause == cause
      }
    XCTAssertEqual(found?.cause, cause, lines, file: file, line: line)
    XCTAssertTrue(
      found?.line.contains(words) ?? false, lines, file: file, line: line)
    XCTAssertTrue(
      found?.line.hasPrefix(found?.shape ?? "?") ?? false, lines,
      file: file, line: line)
    XCTAssertTrue(
      report.lines.last?.hasPrefix("the images were not compared") ?? false,
      lines, file: file, line: line)
  }

  // MARK: - The course's shapes and the slides' formulas pass

  func testTheCoursesShapes_PassEveryProbe() {
    let report = ShapeProbes.probe(Set(ProbedKind.allCases))
    XCTAssertTrue(report.passes, report.lines.joined(separator: "\n"))
    XCTAssertEqual(
      report.probed.map(\.name), ["Sphere", "Plane", "Triangle", "Transform"])
    XCTAssertEqual(report.probed.map(\.probes), [9, 7, 10, 4])
    XCTAssertEqual(report.lines.count, 1)
    XCTAssertTrue(
      report.lines[0].hasSuffix(
        "Sphere passed 9, Plane passed 7, Triangle passed 10, Transform "
          + "passed 4"), report.lines[0])
  }

  /// The lecture's answers, written as the slides write them (the
  /// textbook quadratic, Cramer's rule), pass too: the probes ask for no
  /// more than the contract.
  func testTheSlidesFormulas_PassEveryProbe() {
    let report = ShapeProbes.probe(
      Set(ProbedKind.allCases),
      factories: factories(
        sphere: .none, plane: .none, triangle: .none, transform: .none))
    XCTAssertTrue(report.passes, report.lines.joined(separator: "\n"))
    XCTAssertEqual(report.probed.map(\.failed), [0, 0, 0, 0])
  }

  /// Only the kinds a scene uses are asked (a week's handout need not
  /// have the later shapes written); a transform's probes need the
  /// sphere's.
  func testTheScenesKinds_AreProbed() throws {
    func names(_ scene: String) throws -> [String] {
      let read = try SceneReader.read(
        contentsOf: "\(projectFolder)/scenes/\(scene)",
        options: SceneOptions(style: .course))
      return ShapeProbes.check(read).probed.map(\.name)
    }
    XCTAssertEqual(try names("spheres-only.txt"), ["Sphere"])
    XCTAssertEqual(
      try names("mesh-and-transforms.txt"),
      ["Sphere", "Plane", "Triangle", "Transform"])
    let report = probe(.transform) { $0.sphere = slideSphere(.farRoot) }
    XCTAssertEqual(report.probed.map(\.name), ["Sphere"])
    XCTAssertTrue(
      report.notes.contains { $0.hasPrefix("Transform: not probed") },
      report.lines.joined(separator: "\n"))
  }

  // MARK: - The sphere's mistakes

  func testSphere_CentreNotSubtracted() {
    let report = probe(.sphere) { $0.sphere = slideSphere(.centreForgotten) }
    assertNames(report, .centreNotSubtracted, "the centre is not subtracted")
    XCTAssertEqual(
      report.diagnoses.count, 1,
      "the tangent, inside and long rays fail too, but the moved sphere "
        + "says why: \(report.lines)")
  }

  func testSphere_FarRoot() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.farRoot) }, .farRoot,
      "t = 12 is the far root")
  }

  func testSphere_HitsBehindTheEye() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.nearRootWhatever) },
      .hitBehind, "hits behind the eye")
  }

  func testSphere_NoDiscriminantTest() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.noDiscriminantTest) },
      .discriminantTest, "b² − 4ac < 0")
  }

  func testSphere_TangentMissed() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.discriminantPositive) },
      .tangentMissed, "not > 0")
  }

  func testSphere_InsideMissed() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.nearRootOnly) },
      .insideMissed, "from inside")
  }

  func testSphere_DirectionNormalised() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.directionNormalised) },
      .directionNormalised, "the direction was normalised")
  }

  func testSphere_AOfOne() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.aIsOne) },
      .directionLength, "a = d·d, not 1")
  }

  func testSphere_NormalNotNormalised() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.normalNotNormalised) },
      .normalNotUnit, "the normal has length 2 (the radius is 2)")
  }

  func testSphere_NormalPointsIn() {
    assertNames(
      probe(.sphere) { $0.sphere = slideSphere(.normalIn) },
      .normalTurned, "points into the sphere")
  }

  // MARK: - The plane's mistakes

  func testPlane_OffsetSign() {
    assertNames(
      probe(.plane) { $0.plane = slidePlane(.offsetFlipped) }, .offsetSign,
      "the offset's sign")
  }

  func testPlane_OneSided() {
    assertNames(
      probe(.plane) { $0.plane = slidePlane(.oneSided) }, .backSideMissed,
      "a plane has two sides")
  }

  func testPlane_NormalTurnedTowardsTheRay() {
    assertNames(
      probe(.plane) { $0.plane = slidePlane(.normalTowardsTheRay) },
      .normalTurned, "the plane's own")
  }

  func testPlane_Parallel() {
    assertNames(
      probe(.plane) { $0.plane = slidePlane(.tMinOnly) }, .parallelHit,
      "parallel to the plane")
    assertNames(
      probe(.plane) { $0.plane = slidePlane(.intervalByExclusion) },
      .parallelHit, "within it")
  }

  func testPlane_DirectionNormalised() {
    assertNames(
      probe(.plane) { $0.plane = slidePlane(.directionNormalised) },
      .directionNormalised, "|d| = 5")
  }

  // MARK: - The triangle's mistakes

  func testTriangle_EachEdgeTest() {
    for (mistake, cause, words) in [
      (CramerTriangle.Mistake.noBetaTest, ProbeCause.edgeBeta, "test β ≥ 0"),
      (.noGammaTest, .edgeGamma, "test γ ≥ 0"),
      (.noSumTest, .edgeSum, "test β + γ ≤ 1"),
    ] {
      assertNames(
        probe(.triangle) { $0.triangle = cramerTriangle(mistake) }, cause,
        words)
    }
  }

  func testTriangle_BackFaceCulled() {
    assertNames(
      probe(.triangle) { $0.triangle = cramerTriangle(.culled) },
      .backSideMissed, "a ray from the back hits too")
  }

  func testTriangle_WindingReversed() {
    assertNames(
      probe(.triangle) { $0.triangle = cramerTriangle(.windingReversed) },
      .normalTurned, "not (c − a) × (b − a)")
  }

  func testTriangle_VertexNormalsAndTextureCoordinates() {
    assertNames(
      probe(.triangle) { $0.triangle = cramerTriangle(.flatNormal) },
      .normalsNotInterpolated, "the vertex normals are not used")
    assertNames(
      probe(.triangle) { $0.triangle = cramerTriangle(.noTexture) },
      .textureNotInterpolated, "no texture coordinate")
    assertNames(
      probe(.triangle) { $0.triangle = cramerTriangle(.weightsSwapped) },
      .normalDirection, "(1 − β − γ)·n0 + β·n1 + γ·n2")
  }

  func testTriangle_DirectionNormalised() {
    assertNames(
      probe(.triangle) { $0.triangle = cramerTriangle(.directionNormalised) },
      .directionNormalised, "|d| = 2")
  }

  // MARK: - The transform's mistakes

  func testTransform_NormalByM() {
    assertNames(
      probe(.transform) { $0.transform = slideTransform(.normalByMatrix) },
      .normalByMatrix, "inverse transpose")
  }

  func testTransform_NormalByTheInverseUntransposed() {
    assertNames(
      probe(.transform) { $0.transform = slideTransform(.normalByInverse) },
      .normalByInverse, "transpose it")
  }

  func testTransform_NormalLeftInObjectSpace() {
    assertNames(
      probe(.transform) { $0.transform = slideTransform(.normalUnmoved) },
      .normalInObjectSpace, "left in object space")
  }

  func testTransform_NormalNotNormalised() {
    assertNames(
      probe(.transform) {
        $0.transform = slideTransform(.normalNotNormalised)
      }, .normalNotUnit, "has length 0.5")
  }

  func testTransform_ObjectDirectionNormalised() {
    assertNames(
      probe(.transform) {
        $0.transform = slideTransform(.objectDirectionNormalised)
      }, .objectDirectionNormalised, "t = 4 is measured in object space")
  }

  func testTransform_OriginAsADirection() {
    assertNames(
      probe(.transform) { $0.transform = slideTransform(.originAsDirection) },
      .objectOrigin, "M⁻¹·(o, 1), a point")
  }

  func testTransform_WorldDirectionNormalised() {
    assertNames(
      probe(.transform) {
        $0.transform = slideTransform(.worldDirectionNormalised)
      }, .directionNormalised, "do not normalise it")
  }
}
