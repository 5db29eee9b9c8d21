import ExactArithmetic
import Geometry
import SceneDescription

/// The constants a camera-relative intersection needs, computed from the
/// scene's values in twice their precision and rounded once to the render's.
///
/// Every camera ray starts at the eye, so the differences eye − centre and the
/// products in |p|² − r² and d − n·eye are the same for every pixel: computing
/// them once, carefully, both removes them from the per-ray loop and removes
/// the cancellations that ruin planets and far-from-origin scenes.
@usableFromInline
package enum CameraRelative {
  /// p = centre − eye rounded to nearest, and c = |p|² − r² with no
  /// cancellation beyond the final rounding.
  @usableFromInline
  package static func sphere<Input: RayScalar, S: RayScalar>(
    center: Vector3<Input>, radius: Input, eye: Vector3<Input>,
    as: S.Type = S.self
  ) -> (offset: Vector3<S>, c: S) {
    let dx = Compensated.twoSum(center.x, -eye.x)
    let dy = Compensated.twoSum(center.y, -eye.y)
    let dz = Compensated.twoSum(center.z, -eye.z)
    let radiusSquared = Compensated.twoProduct(radius, radius)
    let offset = Vector3<S>(
      narrowed(dx.sum, dx.error), narrowed(dy.sum, dy.error),
      narrowed(dz.sum, dz.error))
    // On the stack: this runs once per sphere, a million times for the
    // largest scenes.
    func sum(keepingZeros: Bool) -> S {
      withUnsafeTemporaryAllocation(of: Input.self, capacity: 14) { terms in
        var count = 0
        func append(_ term: Input) {
          guard keepingZeros || term != 0 else { return }
          terms[count] = term
          count += 1
        }
        func appendSquare(_ d: (sum: Input, error: Input)) {
          let square = Compensated.twoProduct(d.sum, d.sum)
          append(square.product)
          append(square.error)
          append(2 * d.sum * d.error)
          append(d.error * d.error)
        }
        appendSquare(dx)
        appendSquare(dy)
        appendSquare(dz)
        append(-radiusSquared.product)
        append(-radiusSquared.error)
        return roundedSum(
          UnsafeMutableBufferPointer(rebasing: terms[0..<count]))
      }
    }
    // Zero terms (two for each coordinate where centre − eye is exact, as
    // for an eye on an axis) sort last and add nothing: left out, the sum
    // is the same in fewer steps, up to the sign of a zero result, which
    // the full sum then settles.
    var c = sum(keepingZeros: false)
    if c == 0 { c = sum(keepingZeros: true) }
    return (offset, c)
  }

  /// k = offset − n·eye, the signed distance from the eye to the plane
  /// n·P = offset (negated), evaluated without cancellation.
  @usableFromInline
  package static func plane<Input: RayScalar, S: RayScalar>(
    normal: Vector3<Input>, offset: Input, eye: Vector3<Input>,
    as: S.Type = S.self
  ) -> S {
    let px = Compensated.twoProduct(normal.x, eye.x)
    let py = Compensated.twoProduct(normal.y, eye.y)
    let pz = Compensated.twoProduct(normal.z, eye.z)
    // Planes are few: an array is fine here.
    var terms = [
      offset, -px.product, -px.error, -py.product, -py.error, -pz.product,
      -pz.error,
    ]
    return terms.withUnsafeMutableBufferPointer { roundedSum($0) }
  }

  /// The sum of exact terms, rounded once to S: Sum2 in the input type, or
  /// in S itself when S is wider (the Float80 reference from Double input).
  static func roundedSum<Input: RayScalar, S: RayScalar>(
    _ terms: UnsafeMutableBufferPointer<Input>
  ) -> S {
    // Adding the large terms first keeps Sum2's error term small. A stable
    // insertion sort: at most 14 terms, a million times for the largest
    // scenes, where the library's sort cost more than the sums.
    for next in terms.indices.dropFirst() {
      let term = terms[next]
      var slot = next
      while slot > 0 && terms[slot - 1].magnitude < term.magnitude {
        terms[slot] = terms[slot - 1]
        slot -= 1
      }
      terms[slot] = term
    }
    if S.significandBitCount > Input.significandBitCount {
      return Compensated.sum(terms.lazy.map { S($0) })
    }
    let pair = Compensated.sumPair(terms)
    return narrowed(pair.sum, pair.error)
  }

  /// sum + error (exact, |error| ≤ ulp(sum)/2) in S, rounded once.
  @usableFromInline
  package static func narrowed<Input: RayScalar, S: RayScalar>(
    _ sum: Input, _ error: Input
  ) -> S {
    if S.significandBitCount > Input.significandBitCount {
      return S(sum) + S(error)
    }
    if S.significandBitCount == Input.significandBitCount {
      return S(sum + error)
    }
    return Compensated.narrow(sum, error)
  }
}
