import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

extension Matrix4Tests {
  // MARK: - Inverse

  /// Exact inverses: translations negate, power-of-two scales invert
  /// exactly, and the identity is its own inverse.
  func checkExactInverses<T: RayScalar>(_: T.Type) {
    XCTAssertEqual(Matrix4<T>.identity.inverse(), .identity)
    XCTAssertEqual(
      Matrix4<T>.translation(Vector3(3, -0.5, 1e3)).inverse(),
      .translation(Vector3(-3, 0.5, -1e3)))
    XCTAssertEqual(
      Matrix4<T>.scale(Vector3(2, 0.25, -8)).inverse(),
      .scale(Vector3(0.5, 4, -0.125)))
    let m =
      Matrix4<T>.translation(Vector3(4, 2, 1)) * .scale(Vector3(2, 4, 0.5))
    XCTAssertEqual(
      m.inverse(),
      Matrix4<T>.scale(Vector3(0.5, 0.25, 2))
        * .translation(Vector3(-4, -2, -1)))
  }

  func testInverse_Exact_Float() { checkExactInverses(Float.self) }
  func testInverse_Exact_Double() { checkExactInverses(Double.self) }

  /// Equilibration makes invertibility independent of units: a uniformly
  /// tiny or huge scale, and a tiny scale beside a large translation, are
  /// inverted (exactly, for powers of two), where an unscaled pivot test
  /// would call them singular.
  func checkInverseOfExtremeScales<T: RayScalar>(_: T.Type) {
    let tiny = T(
      sign: .plus, exponent: T.leastNormalMagnitude.exponent / 2, significand: 1
    )
    let huge = 1 / tiny
    XCTAssertEqual(
      Matrix4<T>.uniformScale(tiny).inverse(), .uniformScale(huge), "\(T.self)")
    XCTAssertEqual(
      Matrix4<T>.scale(Vector3(huge, 1, tiny)).inverse(),
      .scale(Vector3(tiny, 1, huge)), "\(T.self)")
    let shifted = Matrix4<T>.translation(Vector3(4, 0, 0)) * .uniformScale(tiny)
    let inverse = shifted.inverse()
    XCTAssertNotNil(inverse, "\(T.self)")
    XCTAssertEqual(
      inverse, Matrix4<T>.uniformScale(huge) * .translation(Vector3(-4, 0, 0)),
      "\(T.self): exact, powers of two")
  }

  func testInverse_ExtremeScales_Float() {
    checkInverseOfExtremeScales(Float.self)
  }
  func testInverse_ExtremeScales_Double() {
    checkInverseOfExtremeScales(Double.self)
  }

  /// M⁻¹·M = I and M·M⁻¹ = I within 4ε·κ∞ (normwise, largest entry of the
  /// residual), for random products of translations (|t| ≤ 100), scales
  /// (|s| in [1/4, 4], either sign) and rotations, on their linear part L;
  /// and for random projective matrices with a dominant diagonal, whole.
  /// Budget: Gauss–Jordan with partial pivoting has a residual of order
  /// nε·κ with n ≤ 4, and the measured constant is about 1.2.
  ///
  /// The translation column of M⁻¹·M is 0 within 2 ulps of
  /// (|M⁻¹|·|M|)ᵢ₃: −L⁻¹t is one 3-term dot product, within γ₃ = 1.5ε of
  /// |L⁻¹|·|t|, whatever L⁻¹'s own error. Residuals are formed in
  /// ReferenceScalar, and κ∞ from its inverse. The worst are printed.
  func checkInverseResidual<T: RayScalar>(_: T.Type) {
    typealias R = ReferenceScalar
    var worst = (normwise: 0.0, translation: 0.0)
    forEachSeed(1000, base: 0x4D41_0002) { generator, seed in
      let projective = seed % 5 == 0
      let matrix: Matrix4<T>
      if projective {
        var entries: [T] = (0..<16).map { _ in generator.uniform(-1...1) }
        for diagonal in stride(from: 0, to: 16, by: 5) {
          entries[diagonal] += generator.sign() * 4
        }
        matrix = Matrix4(rows: entries)
      } else {
        matrix = randomTransform(using: &generator)
      }
      guard let inverse = matrix.inverse(),
        let exactInverse = Matrix4<R>(matrix).inverse()
      else {
        return XCTFail("\(T.self) seed \(seed): \(matrix) called singular")
      }
      let size = projective ? 4 : 3
      let kappa =
        infinityNorm(Matrix4<R>(matrix), size: size)
        * infinityNorm(exactInverse, size: size)
      for (name, product) in [
        ("M⁻¹M", Matrix4<R>(inverse) * Matrix4<R>(matrix)),
        ("MM⁻¹", Matrix4<R>(matrix) * Matrix4<R>(inverse)),
      ] {
        var deviation: R = 0
        for row in 0..<size {
          for column in 0..<size {
            let identity: R = row == column ? 1 : 0
            deviation = max(
              deviation, (product[row, column] - identity).magnitude)
          }
        }
        let normwise = Double(deviation / (kappa * R(T.ulpOfOne)))
        worst.normwise = max(worst.normwise, normwise)
        XCTAssertLessThanOrEqual(
          normwise, 4,
          "\(T.self) seed \(seed): \(name) − I in units of ε·κ for \(matrix)")
      }
      guard !projective else { return }
      let product = Matrix4<R>(inverse) * Matrix4<R>(matrix)
      let scale = absolute(Matrix4<R>(inverse)) * absolute(Matrix4<R>(matrix))
      for row in 0..<3 {
        let ulps = Double(
          product[row, 3].magnitude / scale[row, 3] / R(T.ulpOfOne))
        worst.translation = max(worst.translation, ulps)
        XCTAssertLessThanOrEqual(
          ulps, 2, "\(T.self) seed \(seed): translation of M⁻¹M for \(matrix)")
      }
    }
    print("\(T.self) worst inverse residuals: \(worst)")
  }

  func testInverse_Residual_Float() { checkInverseResidual(Float.self) }
  func testInverse_Residual_Double() { checkInverseResidual(Double.self) }

  /// Singular matrices give nil: a zero scale, a zero row or column, one
  /// row the sum of two others (exactly, small integers), two equal rows,
  /// a rank-deficient projective matrix, non-finite entries, and a matrix
  /// only ε away from singular, which cannot be inverted meaningfully.
  func checkSingular<T: RayScalar>(_: T.Type) {
    let cases: [(String, Matrix4<T>)] = [
      ("zero scale", .scale(Vector3(1, 0, 1))),
      ("zero matrix", Matrix4(rows: [T](repeating: 0, count: 16))),
      (
        "zero column",
        Matrix4(rows: [0, 1, 2, 3, 0, 5, 6, 7, 0, 9, 1, 2, 0, 0, 0, 1])
      ),
      (
        "row 2 = row 0 + row 1",
        Matrix4(rows: [1, 2, 3, 4, 5, 6, 7, 8, 6, 8, 10, 12, 0, 0, 0, 1])
      ),
      (
        "equal rows",
        Matrix4(rows: [1, 2, 3, 4, 1, 2, 3, 4, 0, 0, 1, 0, 0, 0, 0, 1])
      ),
      (
        "rank 2 projective",
        Matrix4(rows: [1, 2, 3, 4, 2, 4, 6, 8, 3, 6, 9, 12, 1, 1, 1, 1])
      ),
      (
        "flattened by a rotation then a zero scale",
        .scale(Vector3(1, 1, 0)) * .rotationX(degrees: 30)
      ),
      ("NaN entry", .translation(Vector3(T.nan, 0, 0))),
      ("infinite entry", .scale(Vector3(T.infinity, 1, 1))),
      (
        "ε from singular",
        Matrix4(
          rows: [
            1, 1, 0, 0, 1, 1 + T.ulpOfOne, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
          ])
      ),
    ]
    for (name, matrix) in cases {
      XCTAssertNil(matrix.inverse(), "\(T.self): \(name)")
    }
    // The same nearly-singular shape 2⁻⁶ away is comfortably invertible.
    let near = Matrix4<T>(
      rows: [1, 1, 0, 0, 1, 1 + 1 / 64, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    XCTAssertEqual(
      near.inverse(),
      Matrix4(rows: [65, -64, 0, 0, -64, 64, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]),
      "\(T.self): exact, small powers of two")
  }

  func testInverse_Singular_Float() { checkSingular(Float.self) }
  func testInverse_Singular_Double() { checkSingular(Double.self) }
}
