import Geometry
import XCTest

// What the course's tests share: random unit vectors and the error bounds
// every case states, in units of Double's ε (2⁻⁵², about 2.2·10⁻¹⁶).

/// A unit vector uniform over the sphere's directions.
func randomUnit(_ generator: inout SplitMix64) -> Vector3<Double> {
  while true {
    let v = Vector3<Double>(
      .random(in: -1...1, using: &generator),
      .random(in: -1...1, using: &generator),
      .random(in: -1...1, using: &generator))
    let squared = v.lengthSquared
    if squared > 1e-4 && squared <= 1 { return v / squared.squareRoot() }
  }
}

/// Asserts |found − expected| ≤ epsilons·ε·|expected|: the case's relative
/// error bound, `why` the reason for it (the conditioning, the roundings).
func assertRelative(
  _ found: Double?, _ expected: Double, epsilons: Double, _ why: String,
  file: StaticString = #filePath, line: UInt = #line
) {
  guard let found else {
    return XCTFail("nil, not \(expected)", file: file, line: line)
  }
  let error = (found - expected).magnitude / expected.magnitude
  XCTAssert(
    error <= epsilons * .ulpOfOne,
    "\(found), not \(expected): relative error \(error / .ulpOfOne) ε, "
      + "more than the \(epsilons) ε that \(why)", file: file, line: line)
}

/// Asserts that every component of `found` is within epsilons·ε·|expected|
/// of `expected`'s (|·| the largest component): for a unit normal, within
/// epsilons·ε.
func assertClose(
  _ found: Vector3<Double>?, _ expected: Vector3<Double>, epsilons: Double,
  _ why: String, file: StaticString = #filePath, line: UInt = #line
) {
  guard let found else {
    return XCTFail("nil, not \(expected)", file: file, line: line)
  }
  let error = (found - expected).maxMagnitude / expected.maxMagnitude
  XCTAssert(
    error <= epsilons * .ulpOfOne,
    "\(found), not \(expected): off by \(error / .ulpOfOne) ε of its size, "
      + "more than the \(epsilons) ε that \(why)", file: file, line: line)
}

extension Vector3<Double> {
  /// |x| + |y| + |z|: the size of the terms a dot product adds.
  var magnitudeSum: Double { x.magnitude + y.magnitude + z.magnitude }
}
