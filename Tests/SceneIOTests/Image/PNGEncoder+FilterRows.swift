@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

// The whole image filtered at once: what the tests hold the encoder's
// row-by-row filtering (`PNGEncoder.filterRow`) to.
extension PNGEncoder {
  /// Each row prefixed with its filter type byte, the whole image at once.
  static func filterRows(_ image: Image8, _ filter: PNGFilter) -> [UInt8] {
    let stride = image.width * 3
    var out = [UInt8](repeating: 0, count: image.height * (stride + 1))
    var scratch = [UInt8](repeating: 0, count: stride)
    image.bytes.withUnsafeBufferPointer { pixels in
      out.withUnsafeMutableBufferPointer { out in
        scratch.withUnsafeMutableBufferPointer { scratch in
          for row in 0..<image.height {
            let current = UnsafeBufferPointer(
              rebasing: pixels[(row * stride)..<((row + 1) * stride)])
            let previous =
              row > 0
              ? UnsafeBufferPointer(
                rebasing: pixels[((row - 1) * stride)..<(row * stride)])
              : nil
            filterRow(
              current, previous, filter,
              into: UnsafeMutableBufferPointer(
                rebasing: out[(row * (stride + 1))..<((row + 1) * (stride + 1))]
              ), scratch: scratch)
          }
        }
      }
    }
    return out
  }
}
