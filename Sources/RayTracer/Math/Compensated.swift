/// Error-free transformations and the sums and dot products built on them
/// (Ogita, Rump and Oishi, "Accurate sum and dot product", SIAM J. Sci.
/// Comput. 26(6), 2005): results as if computed in twice the working precision
/// and then rounded once.
///
/// They run where cancellation would otherwise lose every digit: the
/// camera-relative sphere constants |p|² − r² of a planet seen from one unit
/// above it, and the denominator n·d of a plane seen at a grazing angle.
public enum Compensated {
  /// s + e == a + b exactly, with s = fl(a + b) (Knuth's TwoSum, no branch).
  @inlinable
  public static func twoSum<S: RayScalar>(_ a: S, _ b: S) -> (sum: S, error: S) {
    let s = a + b
    let bVirtual = s - a
    let aVirtual = s - bVirtual
    return (s, (a - aVirtual) + (b - bVirtual))
  }

  /// p + e == a·b exactly, with p = fl(a·b), using a fused multiply-add.
  @inlinable
  public static func twoProduct<S: RayScalar>(
    _ a: S, _ b: S
  ) -> (product: S, error: S) {
    let p = a * b
    return (p, (-p).addingProduct(a, b))
  }

  /// a·b, as if evaluated in twice the precision and rounded (Dot2).
  ///
  /// Relative error ≤ ε + γ(n)²·cond: a few ulps unless the dot product
  /// cancels by more than 1/ε, where plain evaluation would already have
  /// no correct digit left.
  @inlinable
  public static func dot<S: RayScalar>(
    _ a: Vector3<S>, _ b: Vector3<S>
  ) -> S {
    let px = twoProduct(a.x, b.x)
    let py = twoProduct(a.y, b.y)
    let pz = twoProduct(a.z, b.z)
    let s1 = twoSum(px.product, py.product)
    let s2 = twoSum(s1.sum, pz.product)
    let errors = px.error + py.error + pz.error + s1.error + s2.error
    return s2.sum + errors
  }

  /// Σ terms, as if evaluated in twice the precision and rounded (Sum2).
  @inlinable
  public static func sum<S: RayScalar>(_ terms: [S]) -> S {
    var total: S = 0
    var errors: S = 0
    for term in terms {
      let step = twoSum(total, term)
      total = step.sum
      errors += step.error
    }
    return total + errors
  }
}

/// The constants a camera-relative intersection needs, computed from the
/// scene's values in twice their precision and rounded once to the render's.
///
/// Every camera ray starts at the eye, so the differences eye − centre and the
/// products in |p|² − r² and d − n·eye are the same for every pixel: computing
/// them once, carefully, both removes them from the per-ray loop and removes
/// the cancellations that ruin planets and far-from-origin scenes.
public enum CameraRelative {
  /// p = centre − eye rounded to nearest, and c = |p|² − r² with no
  /// cancellation beyond the final rounding.
  public static func sphere<Input: RayScalar, S: RayScalar>(
    center: Vector3<Input>, radius: Input, eye: Vector3<Input>,
    as: S.Type = S.self
  ) -> (offset: Vector3<S>, c: S) {
    let dx = Compensated.twoSum(center.x, -eye.x)
    let dy = Compensated.twoSum(center.y, -eye.y)
    let dz = Compensated.twoSum(center.z, -eye.z)
    var terms: [Input] = []
    terms.reserveCapacity(13)
    for d in [dx, dy, dz] {
      let square = Compensated.twoProduct(d.sum, d.sum)
      terms.append(square.product)
      terms.append(square.error)
      terms.append(2 * d.sum * d.error)
      terms.append(d.error * d.error)
    }
    let radiusSquared = Compensated.twoProduct(radius, radius)
    terms.append(-radiusSquared.product)
    terms.append(-radiusSquared.error)
    // Adding the large terms first keeps Sum2's error term small.
    terms.sort { $0.magnitude > $1.magnitude }
    let offset = Vector3<S>(
      S(dx.sum) + S(dx.error), S(dy.sum) + S(dy.error), S(dz.sum) + S(dz.error))
    return (offset, roundedSum(terms))
  }

  /// k = offset − n·eye, the signed distance from the eye to the plane
  /// n·P = offset (negated), evaluated without cancellation.
  public static func plane<Input: RayScalar, S: RayScalar>(
    normal: Vector3<Input>, offset: Input, eye: Vector3<Input>,
    as: S.Type = S.self
  ) -> S {
    let px = Compensated.twoProduct(normal.x, eye.x)
    let py = Compensated.twoProduct(normal.y, eye.y)
    let pz = Compensated.twoProduct(normal.z, eye.z)
    var terms = [
      offset, -px.product, -px.error, -py.product, -py.error,
      -pz.product, -pz.error,
    ]
    terms.sort { $0.magnitude > $1.magnitude }
    return roundedSum(terms)
  }

  /// The sum of exact terms, rounded once to S: Sum2 in the input type, or
  /// in S itself when S is wider (the Float80 reference from Double input).
  static func roundedSum<Input: RayScalar, S: RayScalar>(
    _ terms: [Input]
  ) -> S {
    if S.significandBitCount > Input.significandBitCount {
      return Compensated.sum(terms.map { S($0) })
    }
    return S(Compensated.sum(terms))
  }
}
