import CZlib
import Geometry
import SceneDescription
import PlatformSupport

/// Reads back the PNG files this project writes, and any other
/// non-interlaced 8-bit greyscale, RGB or RGBA PNG, checking every chunk's
/// CRC: the tests' and the report's way to look at an image.
package enum PNGDecoder {
  package struct Failure: Error, Equatable, CustomStringConvertible {
    package var description: String
  }

  /// The image as RGB; alpha is dropped and grey is spread to three channels.
  package static func decode(_ bytes: [UInt8]) throws(Failure) -> Image8 {
    guard bytes.count >= 8, Array(bytes[0..<8]) == PNGEncoder.signature else {
      throw Failure(description: "not a PNG file (bad signature)")
    }
    var offset = 8
    var width = 0
    var height = 0
    var channels = 0
    var compressed: [UInt8] = []
    var sawEnd = false
    while !sawEnd {
      guard offset + 12 <= bytes.count else {
        throw Failure(description: "truncated chunk at byte \(offset)")
      }
      let length = Int(readBigEndian(bytes, offset))
      let typeBytes = Array(bytes[(offset + 4)..<(offset + 8)])
      let type = String(decoding: typeBytes, as: UTF8.self)
      guard length <= bytes.count - offset - 12 else {
        throw Failure(
          description: "chunk \(type) runs past the end of the file")
      }
      let data = Array(bytes[(offset + 8)..<(offset + 8 + length)])
      let crc = readBigEndian(bytes, offset + 8 + length)
      guard crc == PNGEncoder.crc32(typeBytes + data) else {
        throw Failure(description: "chunk \(type) has a bad CRC")
      }
      switch type {
      case "IHDR":
        guard data.count == 13 else {
          throw Failure(description: "bad IHDR length")
        }
        width = Int(readBigEndian(data, 0))
        height = Int(readBigEndian(data, 4))
        guard data[8] == 8, data[12] == 0 else {
          throw Failure(
            description: "only 8-bit non-interlaced images are read")
        }
        switch data[9] {
        case 0: channels = 1
        case 2: channels = 3
        case 6: channels = 4
        default:
          throw Failure(description: "colour type \(data[9]) is not read")
        }
      case "IDAT": compressed += data
      case "IEND": sawEnd = true
      default: break
      }
      offset += 12 + length
    }
    guard width > 0, height > 0, channels > 0 else {
      throw Failure(description: "missing or empty IHDR")
    }
    // Sizes a file may claim are checked before anything is allocated: at
    // most 32768 a side, and what decoding takes (the filtered rows, the
    // pixels, the RGB copy) within half of what the process may use.
    guard width <= 1 << 15, height <= 1 << 15 else {
      throw Failure(
        description: "its size \(width)×\(height) is beyond 32768 a side")
    }
    let need = Double(width) * Double(height) * Double(2 * channels + 3)
    if let limit = Memory.limits().first, need > Double(limit.bytes) / 2 {
      throw Failure(
        description: "its \(width)×\(height) pixels would need "
          + "\(Int(need / 1_048_576)) MiB to decode, more than half of what "
          + "the process may use (\(limit.what))")
    }
    let stride = width * channels
    var raw = [UInt8](repeating: 0, count: height * (stride + 1))
    var rawLength = uLongf(raw.count)
    let status = raw.withUnsafeMutableBufferPointer { out in
      compressed.withUnsafeBufferPointer { input in
        uncompress(
          out.baseAddress, &rawLength, input.baseAddress, uLong(input.count))
      }
    }
    guard status == Z_OK, Int(rawLength) == raw.count else {
      throw Failure(description: "IDAT does not inflate to the image's size")
    }
    var pixels = [UInt8](repeating: 0, count: height * stride)
    for row in 0..<height {
      let type = raw[row * (stride + 1)]
      for i in 0..<stride {
        let x = raw[row * (stride + 1) + 1 + i]
        let a = i >= channels ? pixels[row * stride + i - channels] : 0
        let b = row > 0 ? pixels[(row - 1) * stride + i] : 0
        let c =
          row > 0 && i >= channels
          ? pixels[(row - 1) * stride + i - channels] : 0
        let predictor: UInt8
        switch type {
        case 0: predictor = 0
        case 1: predictor = a
        case 2: predictor = b
        case 3: predictor = UInt8((Int(a) + Int(b)) / 2)
        case 4: predictor = PNGEncoder.paeth(a, b, c)
        default:
          throw Failure(description: "row \(row) has filter type \(type)")
        }
        pixels[row * stride + i] = x &+ predictor
      }
    }
    var rgb = [UInt8](repeating: 0, count: width * height * 3)
    for pixel in 0..<(width * height) {
      for channel in 0..<3 {
        rgb[3 * pixel + channel] =
          pixels[pixel * channels + (channels == 1 ? 0 : channel)]
      }
    }
    return Image8(width: width, height: height, bytes: rgb)
  }

  static func readBigEndian(_ bytes: [UInt8], _ offset: Int) -> UInt32 {
    bytes[offset..<(offset + 4)].reduce(0) { $0 << 8 | UInt32($1) }
  }
}
