import XCTest

@testable import Geometry
@testable import ExactArithmetic
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
