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

  /// p + e == a·b exactly, with p = fl(a·b).
  ///
  /// A Float product is exact in Double, which is cheaper than the fused
  /// multiply-add: without FMA in the baseline x86-64 instruction set,
  /// `addingProduct` is a call into libm. For Double that call measured
  /// faster than Dekker and Veltkamp's 17-flop split, so it stays.
  @inlinable @inline(__always)
  public static func twoProduct<S: RayScalar>(
    _ a: S, _ b: S
  ) -> (product: S, error: S) {
    if S.self == Float.self {
      let exact = Double(a) * Double(b)
      let p = S(exact)
      return (p, S(exact - Double(p)))
    }
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
  public static func sum<Terms: Sequence>(_ terms: Terms) -> Terms.Element
  where Terms.Element: RayScalar {
    let pair = sumPair(terms)
    return pair.sum + pair.error
  }

  /// Σ terms as an unevaluated pair sum + error with |error| ≤ ulp(sum)/2,
  /// as if evaluated in twice the precision (Sum2 with its last addition
  /// renormalised by twoSum).
  @inlinable
  public static func sumPair<Terms: Sequence>(
    _ terms: Terms
  ) -> (sum: Terms.Element, error: Terms.Element) where Terms.Element: RayScalar {
    var total: Terms.Element = 0
    var errors: Terms.Element = 0
    for term in terms {
      let step = twoSum(total, term)
      total = step.sum
      errors += step.error
    }
    return twoSum(total, errors)
  }

  /// sum + error rounded once to the narrower type S, where S(sum + error)
  /// would round twice: when sum lies exactly halfway between two S values,
  /// the sign of `error` (not ties-to-even) decides. Elsewhere |error| ≤
  /// ulp(sum)/2 cannot move sum across a midpoint of S, which lies a whole
  /// ulp of Input away or more, so S(sum) is already correct.
  @inlinable
  public static func narrow<Input: RayScalar, S: RayScalar>(
    _ sum: Input, _ error: Input, to _: S.Type = S.self
  ) -> S {
    let rounded = S(sum)
    guard error != 0, rounded.isFinite else { return rounded }
    let difference = sum - Input(rounded)
    guard difference != 0 else { return rounded }
    let neighbour = difference > 0 ? rounded.nextUp : rounded.nextDown
    // The midpoint of two adjacent S values is exact in the wider Input.
    let midpoint = (Input(rounded) + Input(neighbour)) / 2
    guard sum == midpoint else { return rounded }
    return (error > 0) == (difference > 0) ? neighbour : rounded
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
    let radiusSquared = Compensated.twoProduct(radius, radius)
    let offset = Vector3<S>(
      narrowed(dx.sum, dx.error), narrowed(dy.sum, dy.error), narrowed(dz.sum, dz.error))
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
        return roundedSum(UnsafeMutableBufferPointer(rebasing: terms[0..<count]))
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
  public static func plane<Input: RayScalar, S: RayScalar>(
    normal: Vector3<Input>, offset: Input, eye: Vector3<Input>,
    as: S.Type = S.self
  ) -> S {
    let px = Compensated.twoProduct(normal.x, eye.x)
    let py = Compensated.twoProduct(normal.y, eye.y)
    let pz = Compensated.twoProduct(normal.z, eye.z)
    // Planes are few: an array is fine here.
    var terms = [offset, -px.product, -px.error, -py.product, -py.error, -pz.product, -pz.error]
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
  static func narrowed<Input: RayScalar, S: RayScalar>(_ sum: Input, _ error: Input) -> S {
    if S.significandBitCount > Input.significandBitCount {
      return S(sum) + S(error)
    }
    if S.significandBitCount == Input.significandBitCount {
      return S(sum + error)
    }
    return Compensated.narrow(sum, error)
  }
}
