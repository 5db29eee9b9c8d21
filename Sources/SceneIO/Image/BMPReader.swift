import Geometry
import SceneDescription

/// Reads uncompressed Windows bitmaps, the course's texture files: 24-bit
/// (BGR) and 32-bit (BGRA or BGRX, alpha dropped) pixels, rows stored
/// bottom-up (a positive height) or top-down (a negative one), each row
/// padded to 4 bytes. The info header may be any of the Windows versions
/// (40, 52, 56, 108 or 124 bytes); compression must be none, or bit fields
/// that name the standard 32-bit layout. Anything else (palettes, RLE,
/// 16-bit, OS/2 headers, JPEG or PNG inside) is refused by name, and a
/// file shorter than its header says is an error: nothing traps.
package enum BMPReader {
  package struct Failure: Error, Equatable, CustomStringConvertible {
    package var description: String
  }

  /// Larger images are refused rather than allocated: a texture of 2¹⁴
  /// texels on a side is already 800 MB of RGB.
  package static let maximumSide = 1 << 14

  /// The image with its rows from the top, in RGB.
  package static func decode(_ bytes: [UInt8]) throws(Failure) -> Image8 {
    guard bytes.count >= 2, bytes[0] == 0x42, bytes[1] == 0x4D else {
      throw Failure(description: "not a BMP file (it does not start with 'BM')")
    }
    guard bytes.count >= 14 + 40 else {
      throw Failure(
        description: "truncated BMP header: \(bytes.count) bytes, "
          + "at least 54 needed")
    }
    let pixelOffset = Int(uint32(bytes, 10))
    let headerSize = Int(uint32(bytes, 14))
    guard [40, 52, 56, 108, 124].contains(headerSize) else {
      throw Failure(
        description: "unsupported BMP info header of \(headerSize) bytes "
          + "(supported: the Windows headers of 40, 52, 56, 108 or 124)")
    }
    let width = Int(Int32(bitPattern: uint32(bytes, 18)))
    let signedHeight = Int(Int32(bitPattern: uint32(bytes, 22)))
    let planes = uint16(bytes, 26)
    let bitsPerPixel = Int(uint16(bytes, 28))
    let compression = uint32(bytes, 30)
    guard planes == 1 else {
      throw Failure(description: "BMP planes must be 1, found \(planes)")
    }
    guard bitsPerPixel == 24 || bitsPerPixel == 32 else {
      throw Failure(
        description: "\(bitsPerPixel)-bit BMP is not supported "
          + "(only uncompressed 24- and 32-bit)")
    }
    switch compression {
    case 0: break
    case 3 where bitsPerPixel == 32:
      try checkStandardMasks(bytes, headerSize: headerSize)
    default:
      throw Failure(
        description: "compressed BMP (compression \(compression)) is not "
          + "supported (only uncompressed)")
    }
    let height = signedHeight.magnitude
    guard width > 0, height > 0, width <= maximumSide, height <= maximumSide
    else {
      throw Failure(
        description: "BMP size \(width)×\(signedHeight) is out of range "
          + "(1 to \(maximumSide) texels on a side)")
    }
    let bytesPerPixel = bitsPerPixel / 8
    let stride = (width * bytesPerPixel + 3) / 4 * 4
    guard pixelOffset >= 14 + headerSize,
      pixelOffset <= bytes.count,
      bytes.count - pixelOffset >= stride * Int(height)
    else {
      throw Failure(
        description: "truncated BMP: \(width)×\(height) pixels need "
          + "\(stride * Int(height)) bytes from offset \(pixelOffset), "
          + "the file has \(bytes.count) bytes")
    }
    var rgb = [UInt8](repeating: 0, count: width * Int(height) * 3)
    for row in 0..<Int(height) {
      // Bottom-up unless the height is negative.
      let stored = signedHeight > 0 ? Int(height) - 1 - row : row
      let source = pixelOffset + stored * stride
      for column in 0..<width {
        let pixel = source + column * bytesPerPixel
        let target = 3 * (row * width + column)
        rgb[target] = bytes[pixel + 2]
        rgb[target + 1] = bytes[pixel + 1]
        rgb[target + 2] = bytes[pixel]
      }
    }
    return Image8(width: width, height: Int(height), bytes: rgb)
  }

  /// Bit fields are accepted only for the layout plain 32-bit files have:
  /// red, green, blue in bytes 2, 1, 0.
  private static func checkStandardMasks(
    _ bytes: [UInt8], headerSize: Int
  ) throws(Failure) {
    // The masks follow a 40-byte header, or sit inside a longer one.
    guard bytes.count >= 14 + 40 + 12 else {
      throw Failure(description: "truncated BMP: the bit masks are missing")
    }
    let masks = (uint32(bytes, 54), uint32(bytes, 58), uint32(bytes, 62))
    guard masks == (0x00FF_0000, 0x0000_FF00, 0x0000_00FF) else {
      throw Failure(
        description: "BMP bit fields other than 8-bit red, green, blue are "
          + "not supported")
    }
  }

  private static func uint16(_ bytes: [UInt8], _ offset: Int) -> UInt16 {
    UInt16(bytes[offset]) | UInt16(bytes[offset + 1]) << 8
  }

  private static func uint32(_ bytes: [UInt8], _ offset: Int) -> UInt32 {
    UInt32(bytes[offset]) | UInt32(bytes[offset + 1]) << 8
      | UInt32(bytes[offset + 2]) << 16 | UInt32(bytes[offset + 3]) << 24
  }
}
