import Geometry

/// highlight^shininess for the fast engine's Phong highlights: where the
/// shininess is a whole number from 2 to 1024 (the course's materials use
/// 10 to 100) and the render is in Float or Double, by repeated squaring in
/// Double, then rounded once to the render's precision; anywhere else the
/// C library's `pow`, as `Material.Surface.shade` computes every highlight.
///
/// Accuracy: each product rounds once, and a relative error in a power
/// xᵐ is carried into xⁿ n/m times over, so the rounding errors of the
/// squarings and products count at most 2n times in all: xⁿ comes within
/// (1 + 2⁻⁵³)²ⁿ − 1, about 2n·2⁻⁵³ (2⁻⁴² at n = 1024), of itself before
/// the last rounding, while nothing underflows (below 2⁻¹⁰²², within 20
/// of Double's smallest subnormals). In Float that is half an ulp and a
/// trifle; in Double about 2n ulps at most, far below what an 8-bit
/// output resolves (2⁻⁸), and shading writes nothing else but an image of
/// values. x¹ and x⁰ never come here (`specularTerm` returns them
/// itself). `SpecularPowerTests` holds the bound.
///
/// Why: the C library's `pow` took 9 % of the course scene's render and
/// 5–10 % of a supersampled one (docs/PERFORMANCE.md, "Shading in whole
/// powers").
@inlinable
package func specularPower<Scalar: RayScalar>(_ x: Scalar, _ y: Scalar)
  -> Scalar
{
  // The type tests fold away in each specialisation; the generic
  // conversions between floating-point types do not, and cost as much as
  // the power (`perf`).
  if Scalar.self == Double.self,
    let power = wholePower(
      unsafeBitCast(x, to: Double.self), unsafeBitCast(y, to: Double.self))
  {
    return unsafeBitCast(power, to: Scalar.self)
  }
  if Scalar.self == Float.self,
    let power = wholePower(
      Double(unsafeBitCast(x, to: Float.self)),
      Double(unsafeBitCast(y, to: Float.self)))
  {
    return unsafeBitCast(Float(power), to: Scalar.self)
  }
  return Scalar.pow(x, y)
}

/// xʸ by repeated squaring when y is a whole number from 2 to 1024, else
/// nil. A call, not inlined into the shading: inlined, the course scene's
/// 16-sample render ran 0.9 % more instructions (callgrind) and 2.6 %
/// longer.
@usableFromInline @inline(never)
func wholePower(_ x: Double, _ y: Double) -> Double? {
  guard y >= 2, y <= 1024, y.rounded(.towardZero) == y else { return nil }
  var exponent = Int(y)
  var base = x
  var power: Double = 1
  while true {
    if exponent & 1 == 1 { power *= base }
    exponent >>= 1
    if exponent == 0 { return power }
    base *= base
  }
}
