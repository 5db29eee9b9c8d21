import SceneModel

/// How raw depth, normals and colour become 8-bit pixels in each style (the
/// two conventions measured from the course's images; see the README).
extension ImageStyle {
  /// The course's depth images ignore hits this far away or farther.
  public static let courseDepthCutoff = 40.0

  /// The depth range an image uses: the given one, or the course's choice
  /// from the image (nearest hit to farthest hit closer than the cutoff; in
  /// the mit style, which normally takes a range from the command line, the
  /// nearest to the farthest hit). Nil when nothing qualifies.
  public func depthRange<S: RayScalar>(
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

  /// Course: 255 − ⌊255·(t − near)/(far − near)⌋, near white, misses and t
  /// beyond the range black. Mit: (t − near)/(far − near) clamped, near
  /// black, misses black.
  public func depthImage<S: RayScalar>(
    _ buffers: RenderBuffers<S>, range given: ClosedRange<Double>?
  ) -> Image8 {
    depthRows(buffers, range: depthRange(buffers.depth, given: given)).image
  }

  /// `depthImage` a row at a time, for the `range` that `depthRange` gave.
  public func depthRows<S: RayScalar>(
    _ buffers: RenderBuffers<S>, range: ClosedRange<Double>?
  ) -> PixelRows {
    let near = S(range?.lowerBound ?? 0)
    let span = S(range.map { $0.upperBound - $0.lowerBound } ?? 1)
    let far = S(range?.upperBound ?? 0)
    let (width, depth) = (buffers.width, buffers.depth)
    let style = self
    return PixelRows(width: width, height: buffers.height) { row, out in
      depth.withUnsafeBufferPointer { depth in
        for column in 0..<width {
          let t = depth[row * width + column]
          var level: UInt8 = 0
          if t.isFinite {
            let fraction = span > 0 ? (t - near) / span : 0
            switch style {
            case .course:
              // The course's 255 − ⌊255·fraction⌋: inverted after
              // truncating, one level above truncating 1 − fraction
              // wherever 255·fraction is not a whole number.
              if range != nil && t <= far {
                level = 255 - style.quantize(fraction)
              }
            case .mit:
              level = style.quantize(fraction)
            }
          }
          out[3 * column] = level
          out[3 * column + 1] = level
          out[3 * column + 2] = level
        }
      }
    }
  }

  /// Course: |n| per component, misses black. Mit: (n + 1)/2, misses grey.
  public func normalImage<S: RayScalar>(_ buffers: RenderBuffers<S>) -> Image8 {
    if !buffers.normalBytes.isEmpty {
      return Image8(
        width: buffers.width, height: buffers.height,
        bytes: buffers.normalBytes)
    }
    return normalRows(buffers).image
  }

  /// `normalImage` a row at a time.
  public func normalRows<S: RayScalar>(_ buffers: RenderBuffers<S>)
    -> PixelRows
  {
    if !buffers.normalBytes.isEmpty {
      return PixelRows(normalImage(buffers))
    }
    let style = self
    return Self.rows(buffers.normals, buffers) { style.pixel(normal: $0) }
  }

  /// The shaded colour clamped to [0, 1].
  public func colorImage<S: RayScalar>(_ buffers: RenderBuffers<S>) -> Image8 {
    if !buffers.colorBytes.isEmpty {
      return Image8(
        width: buffers.width, height: buffers.height, bytes: buffers.colorBytes)
    }
    return colorRows(buffers).image
  }

  /// `colorImage` a row at a time.
  public func colorRows<S: RayScalar>(_ buffers: RenderBuffers<S>)
    -> PixelRows
  {
    if !buffers.colorBytes.isEmpty {
      return PixelRows(colorImage(buffers))
    }
    let style = self
    return Self.rows(buffers.color, buffers) { style.pixel($0) }
  }

  /// Rows of `values`, one pixel each.
  private static func rows<S: RayScalar, Value: Sendable>(
    _ values: [Value], _ buffers: RenderBuffers<S>,
    _ pixel: @escaping @Sendable (Value) -> (UInt8, UInt8, UInt8)
  ) -> PixelRows {
    let width = buffers.width
    return PixelRows(width: width, height: buffers.height) { row, out in
      values.withUnsafeBufferPointer { values in
        for column in 0..<width {
          let value = pixel(values[row * width + column])
          out[3 * column] = value.0
          out[3 * column + 1] = value.1
          out[3 * column + 2] = value.2
        }
      }
    }
  }

  /// A normal's pixel: |n| per component (course) or (n + 1)/2 (mit),
  /// quantized.
  @inlinable @inline(__always)
  public func pixel<S: RayScalar>(normal: Vector3<S>) -> (UInt8, UInt8, UInt8) {
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
  public func pixel<S: RayScalar>(_ value: Vector3<S>) -> (UInt8, UInt8, UInt8)
  {
    (quantize(value.x), quantize(value.y), quantize(value.z))
  }

  /// [0, 1] to 0...255: truncation in the course style (its `UInt8(v·255)`),
  /// rounding in the mit style; values outside are clamped, NaN is 0.
  @inlinable @inline(__always)
  public func quantize<S: RayScalar>(_ value: S) -> UInt8 {
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
