import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension TriangleMethodTests {
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
}
