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
    let range = depthRange(buffers.depth, given: given)
    let near = S(range?.lowerBound ?? 0)
    let span = S(range.map { $0.upperBound - $0.lowerBound } ?? 1)
    let far = S(range?.upperBound ?? 0)
    var bytes = [UInt8](repeating: 0, count: buffers.depth.count * 3)
    for (pixel, t) in buffers.depth.enumerated() where t.isFinite {
      let fraction = span > 0 ? (t - near) / span : 0
      let level: UInt8
      switch self {
      case .course:
        if range == nil || t > far { continue }
        // The course's 255 − ⌊255·fraction⌋: inverted after truncating,
        // one level above truncating 1 − fraction wherever 255·fraction
        // is not a whole number.
        level = 255 - quantize(fraction)
      case .mit:
        level = quantize(fraction)
      }
      bytes[3 * pixel] = level
      bytes[3 * pixel + 1] = level
      bytes[3 * pixel + 2] = level
    }
    return Image8(width: buffers.width, height: buffers.height, bytes: bytes)
  }

  /// Course: |n| per component, misses black. Mit: (n + 1)/2, misses grey.
  public func normalImage<S: RayScalar>(_ buffers: RenderBuffers<S>) -> Image8 {
    if !buffers.normalBytes.isEmpty {
      return Image8(
        width: buffers.width, height: buffers.height,
        bytes: buffers.normalBytes)
    }
    var bytes = [UInt8](repeating: 0, count: buffers.normals.count * 3)
    for (pixel, normal) in buffers.normals.enumerated() {
      store(self.pixel(normal: normal), at: pixel, in: &bytes)
    }
    return Image8(width: buffers.width, height: buffers.height, bytes: bytes)
  }

  /// The shaded colour clamped to [0, 1].
  public func colorImage<S: RayScalar>(_ buffers: RenderBuffers<S>) -> Image8 {
    if !buffers.colorBytes.isEmpty {
      return Image8(
        width: buffers.width, height: buffers.height, bytes: buffers.colorBytes)
    }
    var bytes = [UInt8](repeating: 0, count: buffers.color.count * 3)
    for (pixel, color) in buffers.color.enumerated() {
      store(self.pixel(color), at: pixel, in: &bytes)
    }
    return Image8(width: buffers.width, height: buffers.height, bytes: bytes)
  }

  /// A normal's pixel: |n| per component (course) or (n + 1)/2 (mit),
  /// quantized.
  @inlinable
  public func pixel<S: RayScalar>(normal: Vector3<S>) -> (UInt8, UInt8, UInt8)
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
  @inlinable
  public func pixel<S: RayScalar>(_ value: Vector3<S>) -> (UInt8, UInt8, UInt8)
  {
    (quantize(value.x), quantize(value.y), quantize(value.z))
  }

  private func store(
    _ value: (UInt8, UInt8, UInt8), at pixel: Int, in bytes: inout [UInt8]
  ) {
    bytes[3 * pixel] = value.0
    bytes[3 * pixel + 1] = value.1
    bytes[3 * pixel + 2] = value.2
  }

  /// [0, 1] to 0...255: truncation in the course style (its `UInt8(v·255)`),
  /// rounding in the mit style; values outside are clamped, NaN is 0.
  @inlinable
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
