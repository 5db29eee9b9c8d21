import XCTest

@testable import Geometry
@testable import ExactArithmetic
import TestSupport

/// `Surface.specularTerm` leaves `pow` out for shininess 0 and 1 and for a
/// black specular colour: the colour must be the one the full product
/// gives, bit for bit, sign of zero included.
final class MaterialSpecularTests: XCTestCase {
  /// Every channel's bits of the shortcut against specular·pow(h, s), for
  /// highlights across (0, 1 + 4ε] (unit vectors give no more) and a few
  /// above, and shininess on and off the shortcuts' paths.
  func checkSameBits<T: RayScalar>(_: T.Type, count: Int) {
    var random = SplitMix64(seed: 41)
    let speculars: [RGB<T>] = [
      .zero, Vector3(-0.0, 0, -0.0), Vector3(0.6, 0.6, 0.6),
      Vector3(0, 0.25, 0), Vector3(1, 1, 1),
    ]
    let shininesses: [T] = [
      0, 1, 0.5, 2, 12, 40, 128, 1024, 1025, -1, -0.0, .nan, .infinity,
    ]
    let highlights: [T] = (0..<count).map { index -> T in
      if index.isMultiple(of: 2) { return random.uniform(0...1) }
      return random.logUniform(T.leastNormalMagnitude, 1)
    }
    let one: T = 1
    let edge: T = 1.0625
    let edges: [T] = [
      one, one.nextUp, one + 4 * T.ulpOfOne, edge, edge.nextUp, 2, 1e30,
      T.leastNonzeroMagnitude,
    ]
    var mismatches = 0
    for specular in speculars {
      for shininess in shininesses {
        let surface = Material<T>.Surface(
          diffuse: Vector3(0.5, 0.5, 0.5), specular: specular,
          shininess: shininess)
        // Every highlight for shininess 1, the one shortcut that rests on
        // the C library; a sample of them otherwise.
        let stride = shininess == 1 ? 1 : 97
        let sampled = Swift.stride(from: 0, to: highlights.count, by: stride)
          .map { highlights[$0] }
        for highlight in sampled + edges where highlight > 0 {
          let fast = surface.specularTerm(highlight)
          let full = specular * T.pow(highlight, shininess)
          let same =
            identical(fast.x, full.x) && identical(fast.y, full.y)
            && identical(fast.z, full.z)
          if !same {
            mismatches += 1
            if mismatches <= 5 {
              XCTFail(
                "\(T.self) specular \(specular) shininess \(shininess) "
                  + "highlight \(highlight): \(fast) against \(full)")
            }
          }
        }
      }
    }
    XCTAssertEqual(mismatches, 0, "\(T.self)")
  }

  /// The same value and sign, or both NaN.
  func identical<T: RayScalar>(_ a: T, _ b: T) -> Bool {
    a.isNaN ? b.isNaN : a == b && a.sign == b.sign
  }

  /// Shininess 1 over 10⁶ highlights: the C library's pow(x, 1) is x.
  func testSpecularTerm_SameBitsAsPow_Double() throws {
    try skipUnlessLongTests()
    checkSameBits(Double.self, count: 1_000_000)
  }

  func testSpecularTerm_SameBitsAsPow_Float() throws {
    try skipUnlessLongTests()
    checkSameBits(Float.self, count: 1_000_000)
  }
}
