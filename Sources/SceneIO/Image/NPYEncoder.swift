import Geometry
import SceneDescription
import PlatformSupport

/// NumPy's `.npy` format, version 1.0: magic, a header dictionary padded so
/// the data starts on a 64-byte boundary, then little-endian values in C
/// order. Shape H×W for one channel, H×W×C otherwise; row 0 at the top.
package enum NPYEncoder {
  /// `<f4` for Float, `<f8` for Double; other types are converted to Double.
  package static func encode<S: RayScalar>(_ image: RawImage<S>) -> [UInt8] {
    let isFloat = S.self == Float.self
    let shape =
      image.channels == 1
      ? "(\(image.height), \(image.width))"
      : "(\(image.height), \(image.width), \(image.channels))"
    var header =
      "{'descr': '\(isFloat ? "<f4" : "<f8")', 'fortran_order': False, "
      + "'shape': \(shape), }"
    let prefixLength = 10
    let padding = 63 - (prefixLength + header.utf8.count) % 64
    header += String(repeating: " ", count: padding) + "\n"
    var bytes: [UInt8] = [0x93] + Array("NUMPY".utf8) + [1, 0]
    let headerLength = UInt16(header.utf8.count)
    bytes.append(UInt8(headerLength & 0xFF))
    bytes.append(UInt8(headerLength >> 8))
    bytes.append(contentsOf: header.utf8)
    bytes.reserveCapacity(bytes.count + image.values.count * (isFloat ? 4 : 8))
    for value in image.values {
      if isFloat {
        withUnsafeBytes(of: Float(value).bitPattern.littleEndian) {
          bytes.append(contentsOf: $0)
        }
      } else {
        withUnsafeBytes(of: Double(value).bitPattern.littleEndian) {
          bytes.append(contentsOf: $0)
        }
      }
    }
    return bytes
  }
}
