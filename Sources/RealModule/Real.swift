// A stand-in for swift-numerics' RealModule, holding only the part raytrace
// uses, under the same names. Deleting this folder and depending on
// swift-numerics instead needs no change to the code that imports it.

/// The elementary functions the renderer needs, as static members so that
/// generic code can call `T.tan(x)` and get the concrete type's libm routine.
public protocol ElementaryFunctions: AdditiveArithmetic {
  static func exp(_ x: Self) -> Self
  static func log(_ x: Self) -> Self
  static func sqrt(_ x: Self) -> Self
  static func sin(_ x: Self) -> Self
  static func cos(_ x: Self) -> Self
  static func tan(_ x: Self) -> Self
  static func acos(_ x: Self) -> Self
  static func atan(_ x: Self) -> Self
  /// `x` raised to the real power `y`; NaN for negative `x`.
  static func pow(_ x: Self, _ y: Self) -> Self
  /// `x` raised to an integer power.
  static func pow(_ x: Self, _ n: Int) -> Self
}

/// Functions beyond the elementary ones, as in swift-numerics.
public protocol RealFunctions: ElementaryFunctions {
  static func atan2(y: Self, x: Self) -> Self
  /// sqrt(x² + y²) without undue overflow or underflow.
  static func hypot(_ x: Self, _ y: Self) -> Self
}

/// A real floating-point type with the elementary functions.
public protocol Real: FloatingPoint, RealFunctions {}
