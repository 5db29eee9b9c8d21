import ExactArithmetic

// The tests' exact reference for whole powers (specular highlights):
// not in Numerics, where no render asks a double-double for one.
extension DoubleDouble {
  /// xⁿ by repeated squaring, each product ≤ 5u²: relative error ≤
  /// 5u²·(2·log₂|n| + 1) roughly, plus one division for negative n. x⁰ = 1.
  package static func pow(_ x: DoubleDouble, _ n: Int) -> DoubleDouble {
    if n == 0 { return 1 }
    var base = x
    var remaining = n.magnitude
    var result: DoubleDouble = 1
    while remaining > 0 {
      if remaining & 1 == 1 { result = result * base }
      remaining >>= 1
      if remaining > 0 { base = base * base }
    }
    return n < 0 ? 1 / result : result
  }
}
