import RealModule

/// A floating-point type the renderer computes in.
///
/// Renders run in `Float` or `Double`; the reference that errors are
/// measured against is `Float80` where the platform has it (x86) and
/// `DoubleDouble` elsewhere (Apple Silicon), both more precise than Double.
/// The choice is made once per render (a render's precision), so
/// every generic function is specialised for the concrete type rather than
/// dispatched through witness tables.
///
/// Of the elementary functions it asks only those a render calls: `tan`
/// (the camera's field of view), `sin` and `cos` (rotations) and `pow`
/// (specular highlights). Float, Double and Float80 take them from their
/// `Real` conformance (RealModule); `DoubleDouble` writes just these.
public protocol RayScalar: BinaryFloatingPoint, Sendable {
  static func sin(_ x: Self) -> Self
  static func cos(_ x: Self) -> Self
  static func tan(_ x: Self) -> Self
  static func pow(_ x: Self, _ y: Self) -> Self
}

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
