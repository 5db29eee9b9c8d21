import Course
import Geometry
import SceneDescription
import XCTest

/// Week 2's stability cases, a group of their own: what the slide's
/// formula (a = d·d, b = 2 f·d, c = f·f − r², (−b ± √(b² − 4ac)) / 2a)
/// loses and the stable form keeps. A correct textbook answer passes
/// `Week2_SphereTests` and fails these: it is not wrong, it loses digits.
/// docs/ACCURACY.md says why and what to write instead.
final class Week2_SphereTests_Stability: XCTestCase {
  /// A small sphere far away (10³ to 10⁶ radii): b² and 4ac are nearly
  /// equal, so b² − 4ac keeps only the digits they do not share, and t
  /// loses half of its own (relative error near 10⁻¹⁰ at 10⁶ radii). The
  /// stable form computes the discriminant as a·(r − |v|)(r + |v|), v the
  /// centre's offset from the ray's line, and the roots as q/a and c/q,
  /// and holds t = L − r to within 2 ulps (one rounding of L − r itself,
  /// one of the root's last operation).
  func testSmallFarSphere_TheDiscriminantMustNotCancel() throws {
    let down = Vector3<Double>(0, 0, -1)
    for (distance, radius) in [(1e3, 1e-3), (1e6, 1.0), (7e5, 0.3)] {
      let small = Sphere(center: Vector3(0, 0, -distance), radius: radius)
      let found = try XCTUnwrap(
        small.intersect(
          Ray(origin: .zero, direction: down), after: 0, before: .infinity),
        "stability: a sphere \(distance / radius) radii away was missed: "
          + "b² − 4ac cancelled to below 0")
      let exact = distance - radius
      let error = (found.t - exact).magnitude
      XCTAssertLessThanOrEqual(
        error, 2 * exact.ulp,
        "stability: t = \(found.t), not \(exact) (L = \(distance), "
          + "r = \(radius); off by \(error / exact.ulp) ulps). b² − 4ac "
          + "cancels for a small far sphere: b² and 4ac agree in their "
          + "leading digits, and their difference keeps only the rest. "
          + "It equals 4a·(r − |v|)(r + |v|), v = f − d·(f·d)/(d·d): "
          + "compute it so, and the roots as q/a and c/q (docs/ACCURACY.md, "
          + "the stable method). The lecture's cases (Week2_SphereTests) "
          + "do not need it")
      XCTAssertEqual(found.normal, Vector3(0, 0, 1))
    }
  }
}
