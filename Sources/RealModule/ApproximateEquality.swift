extension Numeric where Magnitude: FloatingPoint {
  /// Whether `self` and `other` agree within an absolute or a relative
  /// tolerance:
  /// |a − b| ≤ max(absoluteTolerance, relativeTolerance·max(|a|, |b|)).
  ///
  /// Not transitive, so never back `Equatable` with it. Unlike the real
  /// package there is no default relative tolerance: a caller states one, with
  /// its unit and reason.
  @inlinable
  public func isApproximatelyEqual(
    to other: Self,
    absoluteTolerance: Magnitude = 0,
    relativeTolerance: Magnitude
  ) -> Bool {
    precondition(absoluteTolerance >= 0 && relativeTolerance >= 0)
    if self == other { return true }
    let scale = Swift.max(self.magnitude, other.magnitude)
    let difference = (self - other).magnitude
    return difference <= Swift.max(absoluteTolerance, relativeTolerance * scale)
  }
}
