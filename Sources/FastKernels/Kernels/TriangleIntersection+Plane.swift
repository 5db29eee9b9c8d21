import ExactArithmetic
import Geometry
import SceneDescription

/// Triangles much larger than their distance from the ray's origin.
///
/// The watertight test takes t from the sheared vertices, Σ wᵢ·zᵢ / Σ wᵢ:
/// for a ground triangle 10⁶ across seen from one unit above it those z
/// values are 10⁶ while t is a few units, and t keeps only ε·10⁶ of
/// relative accuracy. Such a triangle's t is taken from its plane instead
/// (`TrianglePlane.exact`, as every triangle thin or large enough to lose
/// digits is), while the watertight test still decides hit or miss and
/// gives the barycentrics, so meshes stay watertight.
///
/// `make` decides which triangles are large: those whose vertices reach
/// beyond `reach` times their plane's distance from the origin (decided
/// from the same rounded values in the model and the fast engine, which
/// keeps them in a list of their own outside its hierarchy). The plane it
/// returns, k = n·(v0 − o) from the exact differences v0 − o for the
/// rounded normal n, summed compensated, stands in only where the exact
/// plane cannot be made (vertices exactly collinear in Double but not as
/// rounded).
@usableFromInline
package enum TrianglePlane {
  /// How far (in multiples of its plane's distance from the eye) a
  /// triangle's vertices must reach before its t is taken from the plane.
  @usableFromInline
  package static let reach = 1024.0

  /// The plane of a triangle seen from an origin o: its unit normal n (the
  /// geometric normal of the vertices relative to o) and k = n·(v0 − o),
  /// when the triangle is large beside k; nil otherwise.
  ///
  /// - Parameters:
  ///   - relative: the vertices minus o, rounded to S (as the watertight
  ///     test and the records hold them).
  ///   - v0, origin: the first vertex and o in the scene's precision, from
  ///     which v0 − o is taken exactly.
  @usableFromInline
  package static func make<Input: RayScalar, S: RayScalar>(
    relative: (Vector3<S>, Vector3<S>, Vector3<S>), normal n: Vector3<S>,
    v0: Vector3<Input>, origin: Vector3<Input>
  ) -> (normal: Vector3<S>, distance: S)? {
    let dx = Compensated.twoSum(v0.x, -origin.x)
    let dy = Compensated.twoSum(v0.y, -origin.y)
    let dz = Compensated.twoSum(v0.z, -origin.z)
    let extent = Swift.max(
      relative.0.maxMagnitude, relative.1.maxMagnitude,
      relative.2.maxMagnitude)
    if S.significandBitCount <= Input.significandBitCount {
      // Most triangles are nowhere near large: k to a few ulps, from the
      // rounded differences, settles them without the compensated sum.
      // |k̃ − k| ≤ 4ε·Σ|nᵢ||dᵢ| (three products, two sums, the differences'
      // dropped tails), taken as 16ε; k rounded to S loses at most a
      // relative ε of S, covered by 1 − 2⁻¹⁰. Past this the exact test
      // below decides, so the answer is the same.
      let (nx, ny, nz) = (Input(n.x), Input(n.y), Input(n.z))
      let estimate = nx * dx.sum + ny * dy.sum + nz * dz.sum
      let bound =
        16 * Input.ulpOfOne
        * (nx.magnitude * dx.sum.magnitude + ny.magnitude * dy.sum.magnitude
          + nz.magnitude * dz.sum.magnitude)
      let least = (estimate.magnitude - bound) * (1 - 0x1p-10)
      if Input(extent) <= Input(reach) * least { return nil }
    }
    let k: S
    if S.significandBitCount > Input.significandBitCount {
      // The wider reference: the differences are exact in S.
      var terms: [S] = []
      for (component, d) in [(n.x, dx), (n.y, dy), (n.z, dz)] {
        let high = Compensated.twoProduct(component, S(d.sum))
        let low = Compensated.twoProduct(component, S(d.error))
        terms += [high.product, high.error, low.product, low.error]
      }
      k = Compensated.sum(terms)
    } else {
      // n is exact in the scene's precision, no narrower than S. The twelve
      // terms on the stack: an array per triangle was most of the compile
      // of a million-triangle mesh's own work.
      k = withUnsafeTemporaryAllocation(of: Input.self, capacity: 12) {
        terms in
        var count = 0
        func append(_ component: S, _ d: (sum: Input, error: Input)) {
          let high = Compensated.twoProduct(Input(component), d.sum)
          let low = Compensated.twoProduct(Input(component), d.error)
          terms.initializeElement(at: count, to: high.product)
          terms.initializeElement(at: count + 1, to: high.error)
          terms.initializeElement(at: count + 2, to: low.product)
          terms.initializeElement(at: count + 3, to: low.error)
          count += 4
        }
        append(n.x, dx)
        append(n.y, dy)
        append(n.z, dz)
        return CameraRelative.roundedSum(terms)
      }
    }
    guard extent > S(reach) * k.magnitude else { return nil }
    return (n, k)
  }
}
