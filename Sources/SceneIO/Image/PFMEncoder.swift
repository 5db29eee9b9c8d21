import Geometry
import SceneDescription
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
  package static func encode<S: RayScalar>(
    converting image: RawImage<S>, threads: Int = 1
  ) -> [UInt8] {
    image.values.withUnsafeBufferPointer {
      encode(
        width: image.width, height: image.height, channels: image.channels,
        values: $0, threads: threads)
    }
  }

  /// The file of an image given as `values`, `channels` per pixel, row 0
  /// at the top, each rounded to Float once as it is written: for a
  /// render's normals read in place (`OutputEncoding`), where a flat copy
  /// of them in Double had been 47 MiB of a 1920×1080 render's peak.
  /// Specialised: called from another module, its generic form converted
  /// each value through the type's witnesses, a second for a 1920×1080
  /// render's depth and normals. A large image's rows are converted by up
  /// to `threads` threads, each a band of rows (the same bytes).
  @_specialize(where S == Float)
  @_specialize(where S == Double)
  package static func encode<S: RayScalar>(
    width: Int, height: Int, channels: Int, values: UnsafeBufferPointer<S>,
    threads: Int = 1
  ) -> [UInt8] {
    precondition(channels == 1 || channels == 3)
    precondition(values.count == width * height * channels)
    let magic = channels == 1 ? "Pf" : "PF"
    let header = Array("\(magic)\n\(width) \(height)\n-1.0\n".utf8)
    let rowLength = width * channels
    let count = header.count + 4 * values.count
    let parts = Parallel.parts(
      values.count, threads: threads, from: 1 << 18, minimum: 1 << 17)
    return [UInt8](unsafeUninitializedCapacity: count) { bytes, initialized in
      let raw = UnsafeMutableRawBufferPointer(bytes)
      raw.copyBytes(from: header)
      // The file's k-th row is the image's row height − 1 − k.
      Parallel.inParts(height, parts) { _, fileRows in
        var offset = header.count + 4 * rowLength * fileRows.lowerBound
        for fileRow in fileRows {
          let start = (height - 1 - fileRow) * rowLength
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
