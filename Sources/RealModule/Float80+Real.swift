#if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
  #if canImport(Glibc)
    import Glibc
  #elseif canImport(Darwin)
    import Darwin
  #elseif canImport(Musl)
    import Musl
  #endif

  extension Float80: Real {
    @inlinable public static func exp(_ x: Float80) -> Float80 { expl(x) }
    @inlinable public static func log(_ x: Float80) -> Float80 { logl(x) }
    @inlinable public static func sqrt(_ x: Float80) -> Float80 {
      x.squareRoot()
    }
    @inlinable public static func sin(_ x: Float80) -> Float80 { sinl(x) }
    @inlinable public static func cos(_ x: Float80) -> Float80 { cosl(x) }
    @inlinable public static func tan(_ x: Float80) -> Float80 { tanl(x) }
    @inlinable public static func acos(_ x: Float80) -> Float80 { acosl(x) }
    @inlinable public static func atan(_ x: Float80) -> Float80 { atanl(x) }
    @inlinable public static func pow(_ x: Float80, _ y: Float80) -> Float80 {
      powl(x, y)
    }
    @inlinable public static func pow(_ x: Float80, _ n: Int) -> Float80 {
      powl(x, Float80(n))
    }
    @inlinable public static func atan2(y: Float80, x: Float80) -> Float80 {
      atan2l(y, x)
    }
    @inlinable public static func hypot(_ x: Float80, _ y: Float80) -> Float80 {
      hypotl(x, y)
    }
  }
#endif
