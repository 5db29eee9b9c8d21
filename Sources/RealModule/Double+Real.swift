#if canImport(Glibc)
  import Glibc
#elseif canImport(Darwin)
  import Darwin
#elseif canImport(Musl)
  import Musl
#endif

// Free functions at file scope, where the names mean the C library's and not
// the static members below (which would call themselves).
@usableFromInline func libm_exp(_ x: Double) -> Double { exp(x) }
@usableFromInline func libm_log(_ x: Double) -> Double { log(x) }
@usableFromInline func libm_sin(_ x: Double) -> Double { sin(x) }
@usableFromInline func libm_cos(_ x: Double) -> Double { cos(x) }
@usableFromInline func libm_tan(_ x: Double) -> Double { tan(x) }
@usableFromInline func libm_acos(_ x: Double) -> Double { acos(x) }
@usableFromInline func libm_atan(_ x: Double) -> Double { atan(x) }
@usableFromInline func libm_pow(_ x: Double, _ y: Double) -> Double {
  pow(x, y)
}
@usableFromInline func libm_atan2(_ y: Double, _ x: Double) -> Double {
  atan2(y, x)
}
@usableFromInline func libm_hypot(_ x: Double, _ y: Double) -> Double {
  hypot(x, y)
}

extension Double: Real {
  @inlinable public static func exp(_ x: Double) -> Double { libm_exp(x) }
  @inlinable public static func log(_ x: Double) -> Double { libm_log(x) }
  @inlinable public static func sqrt(_ x: Double) -> Double { x.squareRoot() }
  @inlinable public static func sin(_ x: Double) -> Double { libm_sin(x) }
  @inlinable public static func cos(_ x: Double) -> Double { libm_cos(x) }
  @inlinable public static func tan(_ x: Double) -> Double { libm_tan(x) }
  @inlinable public static func acos(_ x: Double) -> Double { libm_acos(x) }
  @inlinable public static func atan(_ x: Double) -> Double { libm_atan(x) }
  @inlinable public static func pow(_ x: Double, _ y: Double) -> Double {
    libm_pow(x, y)
  }
  @inlinable public static func pow(_ x: Double, _ n: Int) -> Double {
    libm_pow(x, Double(n))
  }
  @inlinable public static func atan2(y: Double, x: Double) -> Double {
    libm_atan2(y, x)
  }
  @inlinable public static func hypot(_ x: Double, _ y: Double) -> Double {
    libm_hypot(x, y)
  }
}
