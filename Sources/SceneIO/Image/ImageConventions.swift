import Geometry
import SceneDescription
import PlatformSupport

/// How raw depth, normals and colour become 8-bit pixels in each style (the
/// two conventions measured from the course's images; see the README).
///
/// The row functions are prespecialised (`@_specialize`): their callers call
/// them from another module, where a `package` generic runs unspecialised,
/// looking up generic metadata for every pixel (5 % of a course-engine
/// render of the bunny, and a shared cache every thread consults).
extension ImageStyle {
  /// Course: 255 − ⌊255·(t − near)/(far − near)⌋, near white, misses and t
  /// beyond the range black. Mit: (t − near)/(far − near) clamped, near
  /// black, misses black.
  package func depthImage<S: RayScalar>(
    _ buffers: RenderBuffers<S>, range given: ClosedRange<Double>?
  ) -> Image8 {
    depthRows(buffers, range: depthRange(buffers.depth, given: given)).image
  }

  /// `depthImage` a row at a time, for the `range` that `depthRange` gave.
  @_specialize(where S == Double)
  @_specialize(where S == Float)
  package func depthRows<S: RayScalar>(
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
  package func normalImage<S: RayScalar>(_ buffers: RenderBuffers<S>)
    -> Image8
  {
    if !buffers.normalBytes.isEmpty {
      return Image8(
        width: buffers.width, height: buffers.height,
        bytes: buffers.normalBytes)
    }
    return normalRows(buffers).image
  }

  /// `normalImage` a row at a time.
  @_specialize(where S == Double)
  @_specialize(where S == Float)
  package func normalRows<S: RayScalar>(_ buffers: RenderBuffers<S>)
    -> PixelRows
  {
    if !buffers.normalBytes.isEmpty {
      return PixelRows(normalImage(buffers))
    }
    let style = self
    return Self.rows(buffers.normals, buffers) { style.pixel(normal: $0) }
  }

  /// The shaded colour clamped to [0, 1].
  package func colorImage<S: RayScalar>(_ buffers: RenderBuffers<S>) -> Image8 {
    if !buffers.colorBytes.isEmpty {
      return Image8(
        width: buffers.width, height: buffers.height, bytes: buffers.colorBytes)
    }
    return colorRows(buffers).image
  }

  /// `colorImage` a row at a time.
  @_specialize(where S == Double)
  @_specialize(where S == Float)
  package func colorRows<S: RayScalar>(_ buffers: RenderBuffers<S>)
    -> PixelRows
  {
    if !buffers.colorBytes.isEmpty {
      return PixelRows(colorImage(buffers))
    }
    let style = self
    return Self.rows(buffers.color, buffers) { style.pixel($0) }
  }

  /// Rows of `values`, one pixel each.
  @_specialize(where S == Double, Value == Vector3<Double>)
  @_specialize(where S == Float, Value == Vector3<Float>)
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
}
