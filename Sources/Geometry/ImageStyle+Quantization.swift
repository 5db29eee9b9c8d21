/// How raw depth, normals and colour become 8-bit values in each style, a
/// value at a time: what a render stores for an 8-bit output
/// (`RenderSettings.quantizedOutputs`) and the writers encode
/// (`ImageConventions` in SceneIO, for whole images).
extension ImageStyle {
  /// The course's depth images ignore hits this far away or farther.
  @usableFromInline
  package static let courseDepthCutoff = 40.0

  /// The depth range an image uses: the given one, or the course's choice
  /// from the image (nearest hit to farthest hit closer than the cutoff; in
  /// the mit style, which is normally given a range, the nearest to the
  /// farthest hit). Nil when nothing qualifies.
  @usableFromInline
  package func depthRange<S: RayScalar>(
    _ depth: [S], given: ClosedRange<Double>?
  ) -> ClosedRange<Double>? {
    if let given { return given }
    let cutoff: S = self == .course ? S(Self.courseDepthCutoff) : .infinity
    var near = S.infinity
    var far = -S.infinity
    for t in depth where t < cutoff {
      near = Swift.min(near, t)
      far = Swift.max(far, t)
    }
    guard near <= far else { return nil }
    return Double(near)...Double(far)
  }

  /// A normal's pixel: |n| per component (course) or (n + 1)/2 (mit),
  /// quantized.
  @inlinable @inline(__always)
  @_specialize(where S == Double)
  @_specialize(where S == Float)
  package func pixel<S: RayScalar>(normal: Vector3<S>)
    -> (UInt8, UInt8, UInt8)
  {
    switch self {
    case .course:
      pixel(
        Vector3(normal.x.magnitude, normal.y.magnitude, normal.z.magnitude))
    case .mit:
      pixel((normal + Vector3(1, 1, 1)) * S(0.5))
    }
  }

  /// A colour's pixel: each component quantized.
  @inlinable @inline(__always)
  @_specialize(where S == Double)
  @_specialize(where S == Float)
  package func pixel<S: RayScalar>(_ value: Vector3<S>) -> (UInt8, UInt8, UInt8)
  {
    (quantize(value.x), quantize(value.y), quantize(value.z))
  }

  /// [0, 1] to 0...255: truncation in the course style (its `UInt8(v·255)`),
  /// rounding in the mit style; values outside are clamped, NaN is 0.
  @inlinable @inline(__always)
  @_specialize(where S == Double)
  @_specialize(where S == Float)
  package func quantize<S: RayScalar>(_ value: S) -> UInt8 {
    guard value > 0 else { return 0 }
    guard value < 1 else { return 255 }
    let scaled = value * 255
    if S.significandBitCount <= Double.significandBitCount {
      // Exact in Double, and truncated by one conversion: converting S to
      // an integer directly is the standard library's generic bit-by-bit
      // path even when specialised, and `rounded` a libm call without
      // SSE4.1; this runs three times a pixel inside the render loop.
      let exact = Double(scaled)
      let whole = Int(exact)
      let up = self == .mit && exact - Double(whole) >= 0.5
      return UInt8(truncatingIfNeeded: up ? whole + 1 : whole)
    }
    // Wider than Double: rounded in S first, then held exactly by Double.
    let whole = self == .course ? scaled.rounded(.towardZero) : scaled.rounded()
    return UInt8(truncatingIfNeeded: Int(Double(whole)))
  }
}

/// How an engine turns a normal or a colour into an 8-bit pixel, for an
/// output written only as an 8-bit image: its style's rule
/// (`RenderSettings.quantization`).
@usableFromInline
package struct Quantization: Sendable {
  @usableFromInline let style: ImageStyle

  @inlinable
  package init(style: ImageStyle) { self.style = style }

  /// A normal's pixel: |n| per component (course) or (n + 1)/2 (mit).
  @inlinable @inline(__always)
  package func pixel<S: RayScalar>(normal: Vector3<S>) -> (UInt8, UInt8, UInt8)
  {
    style.pixel(normal: normal)
  }

  /// A colour's pixel, each component quantised.
  @inlinable @inline(__always)
  @_specialize(where S == Double)
  @_specialize(where S == Float)
  package func pixel<S: RayScalar>(_ value: Vector3<S>) -> (UInt8, UInt8, UInt8)
  {
    style.pixel(value)
  }
}

extension RenderSettings {
  /// How this image's 8-bit outputs quantise normals and colours.
  @inlinable
  package var quantization: Quantization { Quantization(style: style) }
}
