import RealModule

/// A floating-point type the renderer computes in.
///
/// Renders run in `Float` or `Double`; the reference that errors are
/// measured against is `Float80` where the platform has it (x86) and
/// `DoubleDouble` elsewhere (Apple Silicon), both more precise than Double.
/// The choice is made once per render (the fast engine's `Precision`), so
/// every generic function is specialised for the concrete type rather than
/// dispatched through witness tables.
public protocol RayScalar: Real, BinaryFloatingPoint, Sendable {}

extension Float: RayScalar {}
extension Double: RayScalar {}
#if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
  extension Float80: RayScalar {}
#endif

extension RayScalar {
  /// Converts exactly when `self` is representable, otherwise rounds to
  /// nearest; used where Double scene values enter a render precision.
  @inlinable
  static func from(_ value: Double) -> Self { Self(value) }
}
