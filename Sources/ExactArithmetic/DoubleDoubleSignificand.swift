import Geometry

/// A 128-bit unsigned integer: the raw significand of a `DoubleDouble`
/// (its 105 fraction bits, as `significandBitPattern` and in
/// `init(sign:exponentBitPattern:significandBitPattern:)`).
///
/// The standard library's UInt128 needs macOS 15, and the double-double is
/// the reference precisely on Macs, so this type stands in. It is a
/// complete `FixedWidthInteger` (trapping `+ − × ÷` on overflow, wrapping
/// `&+` etc.), written for correctness, not speed: division is bit-serial.
@frozen
@usableFromInline
package struct DoubleDoubleSignificand: Sendable, Hashable {
  /// The upper 64 bits.
  @usableFromInline
  package var high: UInt64
  /// The lower 64 bits.
  @usableFromInline
  package var low: UInt64

  @inlinable
  package init(high: UInt64, low: UInt64) {
    self.high = high
    self.low = low
  }

  /// `self << count` for 0 ≤ count, bits shifted out lost; 0 from 128 on.
  @inlinable
  func shiftedLeft(_ count: Int) -> DoubleDoubleSignificand {
    if count <= 0 { return self }
    if count >= 128 { return DoubleDoubleSignificand(high: 0, low: 0) }
    if count >= 64 {
      return DoubleDoubleSignificand(high: low << (count - 64), low: 0)
    }
    return DoubleDoubleSignificand(
      high: high << count | low >> (64 - count), low: low << count)
  }

  /// `self >> count` for 0 ≤ count; 0 from 128 on.
  @inlinable
  func shiftedRight(_ count: Int) -> DoubleDoubleSignificand {
    if count <= 0 { return self }
    if count >= 128 { return DoubleDoubleSignificand(high: 0, low: 0) }
    if count >= 64 {
      return DoubleDoubleSignificand(high: 0, low: high >> (count - 64))
    }
    return DoubleDoubleSignificand(
      high: high >> count, low: low >> count | high << (64 - count))
  }
}
