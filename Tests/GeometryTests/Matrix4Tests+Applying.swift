import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

extension Matrix4Tests {
  // MARK: - Applying

  /// Points are translated, directions are not; a projective matrix
  /// divides by w.
  func checkApplying<T: RayScalar>(_: T.Type) {
    let m = Matrix4<T>.translation(Vector3(1, 2, 3)) * .rotationZ(degrees: 90)
    XCTAssertEqual(m.transformPoint(Vector3(1, 0, 0)), Vector3(1, 3, 3))
    XCTAssertEqual(m.transformDirection(Vector3(1, 0, 0)), Vector3(0, 1, 0))
    XCTAssertEqual(
      m.transformNormal(Vector3(0, 0, 2)), Vector3(0, 0, 1), "unit")

    // w = z: a perspective division.
    let perspective = Matrix4<T>(
      rows: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0])
    XCTAssertFalse(perspective.isAffine)
    XCTAssertEqual(
      perspective.transformPoint(Vector3(2, 4, 2)), Vector3(1, 2, 1))
    XCTAssertEqual(
      perspective.transformDirection(Vector3(2, 4, 2)), Vector3(2, 4, 2),
      "directions take w = 0: the upper 3×3 only")
  }

  func testApplying_Float() { checkApplying(Float.self) }
  func testApplying_Double() { checkApplying(Double.self) }

  /// A mirror keeps normals outward: scaling x by −1 turns the normal
  /// (1, 0, 0) of the face at x = 1 into (−1, 0, 0), the normal of its image
  /// at x = −1; and the normals of a sphere scaled into an ellipsoid are
  /// the gradient of the ellipsoid's equation.
  func checkNormalExamples<T: RayScalar>(_: T.Type) {
    let mirror = Matrix4<T>.scale(Vector3(-1, 1, 1))
    XCTAssertEqual(mirror.transformNormal(Vector3(1, 0, 0)), Vector3(-1, 0, 0))
    XCTAssertEqual(mirror.transformNormal(Vector3(0, 1, 0)), Vector3(0, 1, 0))

    // The unit sphere scaled by (2, 1, 1): at p = (0.6, 0.8, 0), image
    // q = (1.2, 0.8, 0) on x²/4 + y² + z² = 1, whose normal is
    // (x/2, 2y, 2z)/2 ∝ (0.3, 0.8, 0).
    let stretch = Matrix4<T>.scale(Vector3(2, 1, 1))
    let normal = stretch.transformNormal(Vector3(0.6, 0.8, 0))
    let expected = Vector3<ReferenceScalar>(0.3, 0.8, 0).normalized()
    assertRelativeError(
      normal, expected, ulps: 4,
      "\(T.self): 0.6 and 0.8 round, then one "
        + "product, one sum and the normalisation")
  }

  func testNormal_Examples_Float() { checkNormalExamples(Float.self) }
  func testNormal_Examples_Double() { checkNormalExamples(Double.self) }

  /// For random transforms (non-uniform scales, mirrors, rotations,
  /// translations) and random normals n with tangents t ⟂ n, the
  /// transformed normal is unit length and perpendicular to the
  /// transformed tangents: |n′·(L t)| / |L t| ≤ 4ε. Budget: the unit n′
  /// is off the exact direction by a few ε (each cofactor is two products
  /// and a difference, each component of cof(L)·n a 3-term dot product,
  /// then the normalisation), and its dot product with the unit vector
  /// L t / |L t| (formed in ReferenceScalar) is off by no more than that.
  func checkNormalsStayPerpendicular<T: RayScalar>(_: T.Type) {
    var worst = 0.0
    forEachSeed(500, base: 0x4D41_0003) { generator, seed in
      let matrix: Matrix4<T> = randomTransform(using: &generator)
      let n = generator.unitVector(T.self)
      // Two tangents perpendicular to n as rounded, computed in
      // ReferenceScalar, so that only the normal's error is measured.
      let exactNormal = n.reference
      let helper =
        abs(exactNormal.x) < 0.9
        ? Vector3<ReferenceScalar>(1, 0, 0) : Vector3<ReferenceScalar>(0, 1, 0)
      let t1 = exactNormal.cross(helper)
      let t2 = exactNormal.cross(t1)
      let transformed = matrix.transformNormal(n)
      XCTAssertEqual(
        Double(transformed.reference.length), 1,
        accuracy: 4 * Double(T.ulpOfOne), "\(T.self) seed \(seed): unit length")
      for tangent in [t1, t2] {
        let image = Matrix4<ReferenceScalar>(matrix).transformDirection(tangent)
        let cosine = transformed.reference.dot(image) / image.length
        let ulps = Double(cosine.magnitude / ReferenceScalar(T.ulpOfOne))
        worst = max(worst, ulps)
        XCTAssertLessThanOrEqual(
          ulps, 4, "\(T.self) seed \(seed): n′·Lt / |Lt| for \(matrix)")
      }
    }
    print("\(T.self) worst normal/tangent cosine: \(worst) ulps")
  }

  func testNormal_Perpendicular_Float() {
    checkNormalsStayPerpendicular(Float.self)
  }
  func testNormal_Perpendicular_Double() {
    checkNormalsStayPerpendicular(Double.self)
  }
}
