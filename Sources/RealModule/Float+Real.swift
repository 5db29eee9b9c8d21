#if canImport(Glibc)
  import Glibc
#elseif canImport(Darwin)
  import Darwin
#elseif canImport(Musl)
  import Musl
#endif

extension Float: Real {
  @inlinable public static func exp(_ x: Float) -> Float { expf(x) }
  @inlinable public static func log(_ x: Float) -> Float { logf(x) }
  @inlinable public static func sqrt(_ x: Float) -> Float { x.squareRoot() }
  @inlinable public static func sin(_ x: Float) -> Float { sinf(x) }
  @inlinable public static func cos(_ x: Float) -> Float { cosf(x) }
  @inlinable public static func tan(_ x: Float) -> Float { tanf(x) }
  @inlinable public static func acos(_ x: Float) -> Float { acosf(x) }
  @inlinable public static func atan(_ x: Float) -> Float { atanf(x) }
  @inlinable public static func pow(_ x: Float, _ y: Float) -> Float {
    powf(x, y)
  }
  @inlinable public static func pow(_ x: Float, _ n: Int) -> Float {
    powf(x, Float(n))
  }
  @inlinable public static func atan2(y: Float, x: Float) -> Float {
    atan2f(y, x)
  }
  @inlinable public static func hypot(_ x: Float, _ y: Float) -> Float {
    hypotf(x, y)
  }
}
