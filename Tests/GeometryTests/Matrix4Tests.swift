import XCTest

@testable import Geometry
@testable import Numerics
import TestSupport

final class Matrix4Tests: XCTestCase {
  // MARK: - Construction and products

  /// `init(rows:)` reads row by row, `init(columns:)` column by column, and
  /// the two are transposes; the subscript and `rowMajorEntries` agree.
  func checkReadingOrder<T: RayScalar>(_: T.Type) {
    let entries: [T] = (1...16).map { T($0) }
    let byRows = Matrix4<T>(rows: entries)
    XCTAssertEqual(byRows.m01, 2, "row 0, column 1 is the second number")
    XCTAssertEqual(byRows.m10, 5, "row 1 starts with the fifth number")
    XCTAssertEqual(byRows.m03, 4, "the translation column")
    XCTAssertEqual(byRows.rowMajorEntries, entries)
    for row in 0..<4 {
      for column in 0..<4 {
        XCTAssertEqual(byRows[row, column], entries[4 * row + column])
      }
    }
    let byColumns = Matrix4<T>(columns: entries)
    XCTAssertEqual(byColumns, byRows.transposed())
    XCTAssertEqual(byColumns.m10, 2, "column 0 is the first four numbers")
    XCTAssertEqual(byRows.transposed().transposed(), byRows)

    // An OpenGL-style (column-major) translation by (7, 8, 9).
    let translation = Matrix4<T>(
      columns: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 7, 8, 9, 1])
    XCTAssertEqual(translation, .translation(Vector3(7, 8, 9)))
    XCTAssertEqual(
      translation.transformPoint(Vector3(1, 2, 3)), Vector3(8, 10, 12))

    var edited = Matrix4<T>.identity
    edited[2, 3] = 5
    XCTAssertEqual(edited, .translation(Vector3(0, 0, 5)))
  }

  func testReadingOrder_Float() { checkReadingOrder(Float.self) }
  func testReadingOrder_Double() { checkReadingOrder(Double.self) }

  /// Products of small integers are exact: a hand-computed product, the
  /// identity on either side, associativity, and (AB)ᵀ = BᵀAᵀ.
  func checkProducts<T: RayScalar>(_: T.Type) {
    let a = Matrix4<T>(rows: [1, 2, 0, -1, 0, 1, 3, 2, -2, 0, 1, 4, 0, 0, 0, 1])
    let b = Matrix4<T>(rows: [2, 0, 1, 3, 1, -1, 0, 0, 0, 2, 2, 1, 0, 0, 0, 1])
    let product = Matrix4<T>(
      rows: [4, -2, 1, 2, 1, 5, 6, 5, -4, 2, 0, -1, 0, 0, 0, 1])
    XCTAssertEqual(a * b, product)
    XCTAssertEqual(a * .identity, a)
    XCTAssertEqual(Matrix4<T>.identity * a, a)
    let c = Matrix4<T>.translation(Vector3(1, -2, 3)) * .scale(Vector3(2, 3, 4))
    XCTAssertEqual((a * b) * c, a * (b * c), "exact: small integers")
    XCTAssertEqual((a * b).transposed(), b.transposed() * a.transposed())
    var accumulated = a
    accumulated *= b
    XCTAssertEqual(accumulated, product)

    // Applying a·b applies b first: scale, then translate.
    let m =
      Matrix4<T>.translation(Vector3(5, 0, 0)) * .scale(Vector3(5, 0.25, 0.25))
    XCTAssertEqual(m.transformPoint(Vector3(1, 1, 1)), Vector3(10, 0.25, 0.25))
    XCTAssertEqual(
      m.transformDirection(Vector3(1, 1, 1)), Vector3(5, 0.25, 0.25))
    XCTAssertEqual(Matrix4<T>.uniformScale(3), .scale(Vector3(3, 3, 3)))
    XCTAssertTrue(m.isAffine)
  }

  func testProducts_Float() { checkProducts(Float.self) }
  func testProducts_Double() { checkProducts(Double.self) }

  /// Conversion rounds each entry to nearest.
  func testConversion() {
    let third = 1.0 / 3
    let double = Matrix4<Double>.translation(Vector3(third, 0.1, 2))
    let float = Matrix4<Float>(double)
    XCTAssertEqual(float.m03, Float(third))
    XCTAssertEqual(float.m13, Float(0.1))
    XCTAssertEqual(float.m23, 2)
    XCTAssertEqual(Matrix4<Double>(Matrix4<Float>.identity), .identity)
  }

  // MARK: - Rotations

  /// Right-handed, counter-clockwise looking down each axis towards the
  /// origin: X turns y into z, Y turns z into x, Z turns x into y; at
  /// multiples of 90° every entry is exactly 0 or ±1, whatever the number
  /// of turns.
  func checkRotationsOfAxes<T: RayScalar>(_: T.Type) {
    let x = Vector3<T>(1, 0, 0)
    let y = Vector3<T>(0, 1, 0)
    let z = Vector3<T>(0, 0, 1)
    let cases: [(Matrix4<T>, Vector3<T>, Vector3<T>)] = [
      (.rotationX(degrees: 90), y, z), (.rotationX(degrees: 90), z, -y),
      (.rotationY(degrees: 90), z, x), (.rotationY(degrees: 90), x, -z),
      (.rotationZ(degrees: 90), x, y), (.rotationZ(degrees: 90), y, -x),
      (.rotationZ(degrees: 180), x, -x), (.rotationZ(degrees: -90), x, -y),
      (.rotationZ(degrees: 270), x, -y), (.rotationZ(degrees: -270), x, y),
      (.rotationZ(degrees: 3600 + 90), x, y), (.rotationX(degrees: 0), y, y),
      (.rotationY(degrees: -180), x, -x), (.rotationX(degrees: 360), z, z),
    ]
    for (index, (rotation, from, to)) in cases.enumerated() {
      XCTAssertEqual(
        rotation.transformDirection(from), to, "\(T.self) case \(index)")
      XCTAssertEqual(
        rotation.transformPoint(from), to, "\(T.self) case \(index)")
      XCTAssertEqual(
        rotation.transformNormal(from), to, "\(T.self) case \(index)")
      XCTAssertEqual(
        rotation.inverse(), rotation.transposed(),
        "\(T.self) case \(index): exact, entries 0 and ±1")
    }
    let nan = Matrix4<T>.rotationZ(degrees: .infinity)
    XCTAssertTrue(nan.m00.isNaN, "a non-finite angle gives NaNs, not a trap")
    XCTAssertNil(nan.inverse())
  }

  func testRotationsOfAxes_Float() { checkRotationsOfAxes(Float.self) }
  func testRotationsOfAxes_Double() { checkRotationsOfAxes(Double.self) }

  /// Other angles against ReferenceScalar's cosine and sine: within 3 ulps
  /// (ρ·π/180 rounds twice, which costs at most ρ·cot ρ ≤ 1 ulp each in
  /// the sine and ρ·tan ρ ≤ 0.8 ulp in the cosine for |ρ| ≤ 45°, plus
  /// libm's own error below 1 ulp); each rotation is orthonormal, R·Rᵀ = I
  /// within 4 ulps (three products and two sums of entries ≤ 1).
  func checkRotationAccuracy<T: RayScalar>(_: T.Type) {
    typealias R = ReferenceScalar
    let reason = "two roundings in the argument plus libm"
    forEachSeed(300, base: 0x4D41_0001) { generator, seed in
      let degrees = generator.uniform(-720...720, as: T.self)
      let radians = R(degrees) * R.pi / 180
      let cosine = R.cos(radians)
      let sine = R.sin(radians)
      let rotation = Matrix4<T>.rotationZ(degrees: degrees)
      // Entries near zero are judged on the matrix's scale, 1.
      XCTAssertLessThanOrEqual(
        Double((R(rotation.m00) - cosine).magnitude / R(T.ulpOfOne)),
        3 * max(1, Double(cosine.magnitude)), "\(T.self) \(degrees)°: \(reason)"
      )
      XCTAssertLessThanOrEqual(
        Double((R(rotation.m10) - sine).magnitude / R(T.ulpOfOne)),
        3 * max(1, Double(sine.magnitude)), "\(T.self) \(degrees)°: \(reason)")
      XCTAssertEqual(rotation.m01, -rotation.m10)
      XCTAssertEqual(rotation.m11, rotation.m00)
      for matrix in [
        rotation, Matrix4<T>.rotationX(degrees: degrees),
        Matrix4<T>.rotationY(degrees: degrees),
      ] {
        let residual = maximumDeviationFromIdentity(
          matrix * matrix.transposed())
        XCTAssertLessThanOrEqual(
          residual, 4, "\(T.self) \(degrees)°: R·Rᵀ − I in ulps (seed \(seed))")
      }
    }
  }

  func testRotationAccuracy_Float() { checkRotationAccuracy(Float.self) }
  func testRotationAccuracy_Double() { checkRotationAccuracy(Double.self) }

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

  // MARK: - Helpers

  /// T·R·S with |t| ≤ 100, R a product of random X, Y and Z rotations, and
  /// S scales of magnitude in [1/4, 4] with random signs.
  func randomTransform<T: RayScalar>(
    using generator: inout SplitMix64
  ) -> Matrix4<T> {
    let translation = Vector3<T>(
      generator.uniform(-100...100), generator.uniform(-100...100),
      generator.uniform(-100...100))
    let scale = Vector3<T>(
      generator.sign() * generator.logUniform(0.25, 4),
      generator.sign() * generator.logUniform(0.25, 4),
      generator.sign() * generator.logUniform(0.25, 4))
    return Matrix4<T>.translation(translation)
      * .rotationX(degrees: generator.uniform(-180...180))
      * .rotationY(degrees: generator.uniform(-180...180))
      * .rotationZ(degrees: generator.uniform(-180...180))
      * .scale(scale)
  }

  /// The largest row sum of |entries| over the leading size×size block.
  func infinityNorm(_ m: Matrix4<ReferenceScalar>, size: Int) -> ReferenceScalar
  {
    (0..<size).map { row in
      (0..<size).map { m[row, $0].magnitude }.reduce(0, +)
    }.max() ?? 0
  }

  /// The matrix of the entries' magnitudes.
  func absolute(_ m: Matrix4<ReferenceScalar>) -> Matrix4<ReferenceScalar> {
    Matrix4(rows: m.rowMajorEntries.map(\.magnitude))
  }

  /// max |(M − I)ᵢⱼ| in units of T.ulpOfOne, formed in ReferenceScalar.
  func maximumDeviationFromIdentity<T: RayScalar>(_ m: Matrix4<T>) -> Double {
    maximumDeviationFromIdentity(Matrix4<ReferenceScalar>(m), ulpOf: T.self)
  }

  func maximumDeviationFromIdentity<T: RayScalar>(
    _ m: Matrix4<ReferenceScalar>, ulpOf _: T.Type
  ) -> Double {
    let identity = Matrix4<ReferenceScalar>.identity.rowMajorEntries
    let deviation =
      zip(m.rowMajorEntries, identity)
      .map { ($0 - $1).magnitude }.max() ?? 0
    return Double(deviation / ReferenceScalar(T.ulpOfOne))
  }
}
