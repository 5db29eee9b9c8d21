import Geometry

/// An 8-bit RGB image handed out a row at a time, row 0 at the top: what
/// the encoders read, so that an image computed from a render's buffers
/// (a depth image, say) is never held whole as bytes.
///
/// `fill(row, bytes)` writes the row's 3·width bytes. Rows may be asked
/// for in any order, more than once, and from several threads at once.
package struct PixelRows: Sendable {
  package let width: Int
  package let height: Int
  private let fill: @Sendable (Int, UnsafeMutableBufferPointer<UInt8>) -> Void

  package init(
    width: Int, height: Int,
    fill: @escaping @Sendable (Int, UnsafeMutableBufferPointer<UInt8>) -> Void
  ) {
    self.width = width
    self.height = height
    self.fill = fill
  }

  /// The rows of an image held as bytes (shared, not copied).
  package init(_ image: Image8) {
    let bytes = image.bytes
    let stride = 3 * image.width
    self.init(width: image.width, height: image.height) { row, out in
      bytes.withUnsafeBufferPointer { bytes in
        out.baseAddress!.update(
          from: bytes.baseAddress! + row * stride, count: stride)
      }
    }
  }

  /// The bytes per row: three per pixel.
  package var stride: Int { 3 * width }

  /// Writes `row` into `bytes`, which must hold `stride` bytes.
  package func fill(row: Int, into bytes: UnsafeMutableBufferPointer<UInt8>) {
    precondition(row >= 0 && row < height && bytes.count >= stride)
    fill(row, bytes)
  }

  /// Every row, as one image.
  package var image: Image8 {
    var bytes = [UInt8](repeating: 0, count: height * stride)
    bytes.withUnsafeMutableBufferPointer { bytes in
      for row in 0..<height {
        fill(
          row: row,
          into: UnsafeMutableBufferPointer(
            rebasing: bytes[(row * stride)..<((row + 1) * stride)]))
      }
    }
    return Image8(width: width, height: height, bytes: bytes)
  }
}
