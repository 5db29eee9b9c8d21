import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// Portable float map: `Pf` (one channel) or `PF` (three), the size, then a
/// negative scale meaning little-endian, then 32-bit floats with the bottom
/// row first, as the format defines.
package enum PFMEncoder {
  package static func encode(_ image: RawImage<Float>) -> [UInt8] {
    encode(converting: image)
  }

  /// The file of `image`'s values, each rounded to Float once as it is
  /// written (the same bytes as converting the image first, without the
  /// converted copy).
  package static func encode<S: RayScalar>(converting image: RawImage<S>)
    -> [UInt8]
  {
    precondition(image.channels == 1 || image.channels == 3)
    let magic = image.channels == 1 ? "Pf" : "PF"
    let header = Array("\(magic)\n\(image.width) \(image.height)\n-1.0\n".utf8)
    let rowLength = image.width * image.channels
    let count = header.count + 4 * image.values.count
    return [UInt8](unsafeUninitializedCapacity: count) { bytes, initialized in
      let raw = UnsafeMutableRawBufferPointer(bytes)
      raw.copyBytes(from: header)
      var offset = header.count
      image.values.withUnsafeBufferPointer { values in
        for row in stride(from: image.height - 1, through: 0, by: -1) {
          let start = row * rowLength
          for value in values[start..<(start + rowLength)] {
            raw.storeBytes(
              of: Float(value).bitPattern.littleEndian, toByteOffset: offset,
              as: UInt32.self)
            offset += 4
          }
        }
      }
      initialized = count
    }
  }
}
