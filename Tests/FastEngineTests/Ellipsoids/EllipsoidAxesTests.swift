import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `EllipsoidAxes` checked exactly against the Double matrix it was given,
/// in exact arithmetic (`ExactDyadic`; each axis as the exact sum of its
/// two Doubles), so that nothing of the decomposition's own arithmetic is
/// reused. With L = U·diag(σ)·Vᵀ and σⱼ = Aⱼ/r:
/// - the axes uⱼ are orthonormal;
/// - σ's symmetric functions are L's invariants: Σσ² = ‖L‖²_F,
///   Σσᵢ²σⱼ² = ‖cof L‖²_F (the squared 2×2 minors), Πσ² = det²; with the
///   σ's apart, each relatively accurate exactly when these are;
/// - each uⱼ is an eigenvector of LLᵀ for σⱼ²: |LLᵀuⱼ − σⱼ²uⱼ| / σ_max².
///
/// Bounds: orthonormal to 2⁻¹⁰⁰; a scale and a rotation in either order,
/// or a scale on either side of a general well-conditioned matrix (L's
/// columns or its rows carry the scales), hold every invariant, the
/// determinant included, to 2⁻⁹⁸ relative at every aspect up to 10³⁰⁰
/// (DoubleDouble's few units of 2⁻¹⁰⁴: measured at most 2⁻¹⁰¹·⁶); a
/// scale between two rotations is held to 2⁻¹⁰⁴·σ_max, so its determinant
/// to 2⁻⁹⁸·σ_max/σ_min; the residuals are within 2⁻⁹⁸ in all cases
/// (measured at most 2⁻¹⁰³·²).
final class EllipsoidAxesTests: XCTestCase {
  typealias Exact = ExactDyadic
  typealias Scaled = ScaledDoubleDouble

  struct Errors {
    var orthonormal = 0.0
    /// Relative errors of Σσ², Σσᵢ²σⱼ², Πσ².
    var invariants = [0.0, 0.0, 0.0]
    var residual = 0.0
  }

  func errors(
    _ matrix: Matrix4<Double>, radius: Double = 1
  ) throws -> Errors {
    let axes = try XCTUnwrap(
      EllipsoidAxes(
        matrix: matrix, sphere: Sphere(center: .zero, radius: radius)))
    let l = [
      [matrix.m00, matrix.m01, matrix.m02],
      [matrix.m10, matrix.m11, matrix.m12],
      [matrix.m20, matrix.m21, matrix.m22],
    ].map { $0.map(Exact.init) }
    func exact(_ x: DoubleDouble) -> Exact { Exact(x.hi) + Exact(x.lo) }
    func dot(_ a: [Exact], _ b: [Exact]) -> Exact {
      a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    func relative(_ got: Scaled, _ want: Exact) -> Double {
      ((got - Scaled(want)) / Scaled(want)).magnitude.value.hi
    }
    let u = axes.directions.map { [exact($0.x), exact($0.y), exact($0.z)] }
    let sigma = axes.lengths.map { Scaled($0 / DoubleDouble(radius)) }
    let squares = sigma.map { $0 * $0 }
    var result = Errors()
    for i in 0..<3 {
      for j in 0..<3 {
        let unit = Scaled(dot(u[i], u[j])) - Scaled(i == j ? 1 : 0)
        result.orthonormal = max(result.orthonormal, unit.magnitude.value.hi)
      }
    }
    // The invariants, exactly.
    let frobenius = l.flatMap { $0 }.reduce(Exact.zero) { $0 + $1 * $1 }
    var minors = Exact.zero
    for (r0, r1) in [(0, 1), (0, 2), (1, 2)] {
      for (c0, c1) in [(0, 1), (0, 2), (1, 2)] {
        let minor = l[r0][c0] * l[r1][c1] - l[r0][c1] * l[r1][c0]
        minors = minors + minor * minor
      }
    }
    let determinant =
      l[0][0] * (l[1][1] * l[2][2] - l[1][2] * l[2][1])
      - l[0][1] * (l[1][0] * l[2][2] - l[1][2] * l[2][0])
      + l[0][2] * (l[1][0] * l[2][1] - l[1][1] * l[2][0])
    result.invariants = [
      relative(squares[0] + squares[1] + squares[2], frobenius),
      relative(
        squares[0] * squares[1] + squares[0] * squares[2] + squares[1]
          * squares[2], minors),
      relative(squares[0] * squares[1] * squares[2], determinant * determinant),
    ]
    // LLᵀuⱼ − σⱼ²uⱼ over σ_max².
    let largest = squares.max { $0 < $1 } ?? Scaled(1)
    for j in 0..<3 {
      let lt = (0..<3).map { k in
        l[0][k] * u[j][0] + l[1][k] * u[j][1] + l[2][k] * u[j][2]
      }
      var squaredResidual = Scaled.zero
      for i in 0..<3 {
        let component = Scaled(dot(l[i], lt)) - squares[j] * Scaled(u[j][i])
        squaredResidual = squaredResidual + component * component
      }
      result.residual = max(
        result.residual, (squaredResidual.squareRoot() / largest).value.hi)
    }
    return result
  }

  func scale(aspect exponent: Int) -> Matrix4<Double> {
    let wide = pow(10, Double(exponent / 2))
    let thin = pow(10, -Double(exponent - exponent / 2))
    return .scale(Vector3(wide, 0.5 * wide, thin))
  }

  var turn: Matrix4<Double> {
    .rotationX(degrees: 30) * .rotationZ(degrees: 20)
  }

  func check(
    _ matrix: Matrix4<Double>, determinantBound: Double = 0x1p-98,
    _ label: String
  ) throws {
    let e = try errors(matrix, radius: 3)
    XCTAssertLessThanOrEqual(e.orthonormal, 0x1p-100, "unit axes, \(label)")
    XCTAssertLessThanOrEqual(e.invariants[0], 0x1p-98, "Σσ², \(label)")
    XCTAssertLessThanOrEqual(e.invariants[1], 0x1p-98, "Σσᵢ²σⱼ², \(label)")
    XCTAssertLessThanOrEqual(
      e.invariants[2], determinantBound, "Πσ², \(label)")
    XCTAssertLessThanOrEqual(e.residual, 0x1p-98, "LLᵀu − σ²u, \(label)")
  }

  /// L = R·S: the columns carry the scales.
  func testAxes_ScaleThenRotation() throws {
    for exponent in [1, 6, 16, 30, 100, 150, 300] {
      try check(
        turn * scale(aspect: exponent), "rotation·scale, aspect 1e\(exponent)")
    }
  }

  /// L = S·R: the rows carry the scales.
  func testAxes_RotationThenScale() throws {
    for exponent in [1, 6, 16, 30, 100, 150, 300] {
      try check(
        scale(aspect: exponent) * turn, "scale·rotation, aspect 1e\(exponent)")
    }
  }

  /// A general well-conditioned matrix B scaled on the left (rows) and on
  /// the right (columns).
  func testAxes_ScaledGeneralMatrix() throws {
    var b = Matrix4<Double>.identity
    (b.m00, b.m01, b.m02) = (1, 0.3, 0.2)
    (b.m10, b.m11, b.m12) = (0.5, 1, 0.1)
    (b.m20, b.m21, b.m22) = (0.2, 0.4, 1)
    for exponent in [6, 16, 30, 100, 150, 300] {
      let s = scale(aspect: exponent)
      try check(s * b, "scale·B, aspect 1e\(exponent)")
      try check(b * s, "B·scale, aspect 1e\(exponent)")
    }
  }

  /// A pure scale: the coordinate axes and the scales themselves, exactly.
  func testAxes_PureScale() throws {
    let axes = try XCTUnwrap(
      EllipsoidAxes(
        matrix: .scale(Vector3(1e150, 2, 1e-150)),
        sphere: Sphere(center: Vector3(1, 2, 3), radius: 0.5)))
    XCTAssertEqual(axes.lengths.map(\.hi), [0.5e150, 1, 0.5e-150])
    XCTAssertEqual(axes.lengths.map(\.lo), [0, 0, 0])
    for (j, direction) in axes.directions.enumerated() {
      XCTAssertEqual(direction.x.magnitude, j == 0 ? 1 : 0)
      XCTAssertEqual(direction.y.magnitude, j == 1 ? 1 : 0)
      XCTAssertEqual(direction.z.magnitude, j == 2 ? 1 : 0)
    }
    // L·c exactly: 3·fl(1e-150), not fl(3e-150).
    XCTAssertEqual(
      axes.center, Vector3(DoubleDouble(1e150), 4, DoubleDouble(1e-150) * 3))
  }

  /// R₁·S·R₂: relative to σ_max only.
  func testAxes_ScaleBetweenRotations() throws {
    for exponent in [1, 6, 12] {
      let matrix =
        Matrix4<Double>.rotationX(degrees: 30) * scale(aspect: exponent)
        * .rotationZ(degrees: 20)
      try check(
        matrix, determinantBound: 0x1p-98 * pow(10, Double(exponent)),
        "rotation·scale·rotation, aspect 1e\(exponent)")
    }
  }
}
