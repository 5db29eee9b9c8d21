import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// `ScreenProjection.cornerExtent`, the short way to the screen extent of
/// a triangle's corner (a ball far smaller than its distance): every point
/// of the ball projects inside it, it is as tight as `extent` up to the
/// pads, and past its limit it is `extent`.
final class ScreenProjectionTests: XCTestCase {
  func projection(_ generator: inout SplitMix64) -> ScreenProjection? {
    guard
      let camera = PerspectiveCamera<Double>(
        center: .zero, direction: generator.unitVector(Double.self),
        up: generator.unitVector(Double.self),
        angle: generator.uniform(5...150))
    else { return nil }
    return ScreenProjection(
      camera: camera,
      screen: ScreenMap(style: .course, width: 640, height: 480))
  }

  func interval(_ extent: ScreenProjection.Extent) -> (
    x: (lower: Double, upper: Double), y: (lower: Double, upper: Double)
  )? {
    guard case .within(let x, let y) = extent else { return nil }
    return (x, y)
  }

  func testCornerExtentHoldsTheBall() {
    forEachSeed(300, base: 0xC0_4E7) { generator, _ in
      guard let projection = self.projection(&generator) else { return }
      // A point in front of the eye, within 60° of the view, 10⁻³ to 10⁷
      // away; a ball about it of 10⁻¹² to 2⁻²⁰ of its distance.
      let forward = projection.r3 / projection.r3Length
      let aside = generator.unitVector(Double.self)
      let direction =
        (forward + (aside - forward * aside.dot(forward))
          * generator.uniform(0...1.7))
        .normalized()
      let p = direction * generator.logUniform(1e-3, 1e7)
      let p3 = projection.r3.dot(p)
      let ρ = p3 / projection.r3Length * generator.logUniform(1e-12, 0x1p-20)
      guard let box = interval(projection.cornerExtent(p, reach: ρ)),
        let exact = interval(projection.extent(center: p, reach: ρ))
      else { return XCTFail("a ball in front without a bounded extent") }
      for _ in 0..<64 {
        let q = p + generator.unitVector(Double.self) * ρ
        let x = projection.axes.x.row.dot(q) / projection.r3.dot(q)
        let y = projection.axes.y.row.dot(q) / projection.r3.dot(q)
        XCTAssertTrue(
          box.x.lower <= x && x <= box.x.upper && box.y.lower <= y
            && y <= box.y.upper,
          "a point of the ball outside the corner's extent")
      }
      // Near the ellipse's box: the bound's |rᵢ| + |k| |r₃| against the
      // ellipse's half-width, at most about 3 times it at 60° off the
      // view's axis, plus the pads (2⁻³⁰ of the terms' scale).
      let widths = (box.x.upper - box.x.lower, box.y.upper - box.y.lower)
      let exactWidths = (
        exact.x.upper - exact.x.lower, exact.y.upper - exact.y.lower
      )
      XCTAssertLessThan(widths.0, 4 * exactWidths.0 + 1e-6)
      XCTAssertLessThan(widths.1, 4 * exactWidths.1 + 1e-6)
    }
  }

  /// `triangleExtent`, one reach and pad for three corners: it holds each
  /// corner's `cornerExtent` exactly (the boxes stay conservative) and is
  /// wider than their union by at most 16 times the widest corner's reach
  /// and pad on each side (8 of its widths); it declines where a corner is
  /// not far in front or the corners' depths differ by more than 2×.
  func testTriangleExtentHoldsItsCorners() {
    forEachSeed(300, base: 0x7A1_E47) { generator, _ in
      guard let projection = self.projection(&generator) else { return }
      let forward = projection.r3 / projection.r3Length
      func corner(_ generator: inout SplitMix64) -> Vector3<Double> {
        let aside = generator.unitVector(Double.self)
        return
          (forward + (aside - forward * aside.dot(forward))
            * generator.uniform(0...1.7))
          .normalized()
          * generator.logUniform(1e-3, 1e7)
      }
      // Corners anywhere in view, or a small triangle about one of them.
      let a = corner(&generator)
      let spread = generator.logUniform(1e-9, 1) * a.length
      let (b, c) =
        generator.uniform(0...1) < 0.5
        ? (corner(&generator), corner(&generator))
        : (
          a + generator.unitVector(Double.self) * spread,
          a + generator.unitVector(Double.self) * spread
        )
      let nearest = Swift.min(
        projection.r3.dot(a), projection.r3.dot(b), projection.r3.dot(c))
      let ρ =
        Swift.max(nearest, 0) / projection.r3Length
        * generator.logUniform(1e-12, 0x1p-19)
      guard let (x, y) = projection.triangleExtent(a, b, c, reach: ρ) else {
        // Declined only where some corner is not far in front or the
        // depths differ by more than twice.
        let farthest = Swift.max(
          projection.r3.dot(a), projection.r3.dot(b), projection.r3.dot(c))
        XCTAssertTrue(
          nearest < 0x1p20 * ρ * projection.r3Length
            || farthest > 2 * nearest)
        return
      }
      var widest = (x: 0.0, y: 0.0)
      var union = (
        x: (lower: Double.infinity, upper: -Double.infinity),
        y: (lower: Double.infinity, upper: -Double.infinity)
      )
      for p in [a, b, c] {
        guard let box = interval(projection.cornerExtent(p, reach: ρ)) else {
          return XCTFail("a corner far in front without a bounded extent")
        }
        XCTAssertTrue(
          x.lower <= box.x.lower && box.x.upper <= x.upper
            && y.lower <= box.y.lower && box.y.upper <= y.upper,
          "a corner's extent outside the triangle's")
        union.x = (
          min(union.x.lower, box.x.lower), max(union.x.upper, box.x.upper)
        )
        union.y = (
          min(union.y.lower, box.y.lower), max(union.y.upper, box.y.upper)
        )
        widest = (
          max(widest.x, box.x.upper - box.x.lower),
          max(widest.y, box.y.upper - box.y.lower)
        )
      }
      XCTAssertLessThanOrEqual(
        x.upper - x.lower, (union.x.upper - union.x.lower) + 16 * widest.x)
      XCTAssertLessThanOrEqual(
        y.upper - y.lower, (union.y.upper - union.y.lower) + 16 * widest.y)
    }
    // A corner behind the eye, or at its plane: the way by corners.
    var generator = SplitMix64(seed: 0x7A1_E48)
    guard let projection = self.projection(&generator) else { return }
    let p = projection.r3 / projection.r3Length * 10
    XCTAssertNil(projection.triangleExtent(p, p * 1.01, -p, reach: 1e-9))
    XCTAssertNil(
      projection.triangleExtent(p, p * 1.01, .zero, reach: 1e-9))
    // Anything not finite, in any corner: the way by corners, which gives
    // every pixel. (Min and max alone would pass over a NaN.)
    for bad in [Double.nan, .infinity, -.infinity] {
      for corner in 0..<3 {
        var corners = [p, p * 1.01, p * 1.02]
        corners[corner].y = bad
        XCTAssertNil(
          projection.triangleExtent(
            corners[0], corners[1], corners[2], reach: 1e-9),
          "corner \(corner) with y = \(bad)")
      }
    }
  }

  func testCornerExtentIsTheExtentPastItsLimit() throws {
    var generator = SplitMix64(seed: 0xC0_4E8)
    let projection = try XCTUnwrap(self.projection(&generator))
    let p = projection.r3 / projection.r3Length * 10
    let p3 = projection.r3.dot(p)
    for ρ in [p3 / projection.r3Length * 0x1p-19, 3.0, 20.0] {
      let corner = interval(projection.cornerExtent(p, reach: ρ))
      let ball = interval(projection.extent(center: p, reach: ρ))
      XCTAssertEqual(corner?.x.lower, ball?.x.lower)
      XCTAssertEqual(corner?.y.upper, ball?.y.upper)
    }
    // Behind the eye, as `extent` says.
    guard case .behind = projection.cornerExtent(-p, reach: 1e-9) else {
      return XCTFail("a corner behind the eye")
    }
  }
}
