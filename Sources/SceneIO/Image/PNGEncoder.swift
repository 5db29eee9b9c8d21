import CZlib
import Geometry
import SceneDescription
import PlatformSupport

/// How PNG rows are filtered before compression.
package enum PNGFilter: String, CaseIterable, Sendable {
  /// Raw bytes: fastest to filter, compresses worst.
  case none
  /// Difference from the pixel to the left.
  case sub
  /// Difference from the pixel above.
  case up
  /// Paeth predictor from left, above and upper left.
  case paeth
  /// Per row, whichever of the four has the smallest sum of absolute
  /// differences (the PNG specification's suggested heuristic).
  case adaptive
}

/// The size-against-speed choices for PNG files.
package struct PNGOptions: Hashable, Sendable {
  /// zlib level, 0 (store) to 9 (smallest).
  package var compressionLevel: Int32
  package var filter: PNGFilter

  /// Chosen by measurement on the project's scenes (see the README's PNG
  /// table): ray-cast images are large flat areas and smooth gradients, which
  /// `up` plus a fast zlib level compresses nearly as well as level 9 with
  /// adaptive filtering, several times faster.
  package static let `default` = PNGOptions(compressionLevel: 1, filter: .up)
}

/// Writes 8-bit RGB PNG files: signature, IHDR, one IDAT, IEND, each chunk
/// with its CRC-32, compressed with the system zlib.
///
/// The image data is compressed in pieces of rows, each an independent
/// deflate stream flushed to a byte boundary and the pieces' streams
/// joined into the one zlib stream PNG holds (`PNGEncoder.Pieces`), so that
/// the pieces of one image, or of several, compress on several threads at
/// once. `encode` compresses them one after another.
package enum PNGEncoder {
  static let signature: [UInt8] = [137, 80, 78, 71, 13, 10, 26, 10]

  package static func encode(
    _ image: Image8, options: PNGOptions = .default
  ) -> [UInt8] {
    encode(PixelRows(image), options: options)
  }

  package static func encode(
    _ rows: PixelRows, options: PNGOptions = .default
  ) -> [UInt8] {
    let pieces = Pieces(rows, options: options)
    return pieces.assemble((0..<pieces.count).map(pieces.compress))
  }

  static func appendChunk(
    _ type: String, _ data: [UInt8], to bytes: inout [UInt8]
  ) {
    bytes.appendBigEndian(UInt32(data.count))
    let typeBytes = Array(type.utf8)
    bytes += typeBytes
    bytes += data
    bytes.appendBigEndian(crc32(typeBytes + data))
  }

  /// The CRC-32 that PNG chunks carry (over type and data), from zlib.
  static func crc32(_ bytes: [UInt8]) -> UInt32 {
    bytes.withUnsafeBufferPointer { buffer in
      var crc = CZlib.crc32(0, nil, 0)
      var offset = 0
      // zlib's length is 32-bit: feed very large buffers in slices.
      while offset < buffer.count {
        let length = min(buffer.count - offset, 1 << 30)
        crc = CZlib.crc32(
          crc, buffer.baseAddress.map { $0 + offset }, uInt(length))
        offset += length
      }
      return UInt32(crc)
    }
  }

  /// One row filtered into `target` (stride + 1 bytes): its filter type
  /// byte, then the filtered bytes. `previous` is nil for the first row;
  /// `scratch` (stride bytes) holds the adaptive filter's candidates.
  static func filterRow(
    _ current: UnsafeBufferPointer<UInt8>,
    _ previous: UnsafeBufferPointer<UInt8>?, _ filter: PNGFilter,
    into target: UnsafeMutableBufferPointer<UInt8>,
    scratch: UnsafeMutableBufferPointer<UInt8>
  ) {
    var chosen = filter
    if filter == .adaptive {
      var bestCost = Int.max
      for option in [PNGFilter.none, .sub, .up, .paeth] {
        apply(option, current, previous, into: scratch)
        let cost = scratch.reduce(0) {
          $0 + Int(Int8(bitPattern: $1).magnitude)
        }
        if cost < bestCost {
          bestCost = cost
          chosen = option
        }
      }
    }
    target[0] = chosen.typeByte
    apply(
      chosen, current, previous,
      into: UnsafeMutableBufferPointer(rebasing: target[1...]))
  }

  /// Filters one row; `previous` is nil for the first row (treated as zeros).
  static func apply(
    _ filter: PNGFilter, _ row: UnsafeBufferPointer<UInt8>,
    _ previous: UnsafeBufferPointer<UInt8>?,
    into out: UnsafeMutableBufferPointer<UInt8>
  ) {
    let bytesPerPixel = 3
    // The filters the encoder uses by default, each in a loop of its own
    // that the compiler vectorises: the general loop below, one switch per
    // byte, took a tenth of a course render's whole run.
    switch (filter, previous) {
    case (.none, _), (.up, nil):
      out.baseAddress!.update(from: row.baseAddress!, count: row.count)
      return
    case (.up, let previous?):
      for i in 0..<row.count { out[i] = row[i] &- previous[i] }
      return
    case (.sub, _):
      for i in 0..<Swift.min(bytesPerPixel, row.count) { out[i] = row[i] }
      for i in Swift.min(bytesPerPixel, row.count)..<row.count {
        out[i] = row[i] &- row[i - bytesPerPixel]
      }
      return
    default:
      break
    }
    for i in 0..<row.count {
      let left = i >= bytesPerPixel ? row[i - bytesPerPixel] : 0
      let above = previous?[i] ?? 0
      let upperLeft =
        i >= bytesPerPixel ? (previous?[i - bytesPerPixel] ?? 0) : 0
      let predictor: UInt8
      switch filter {
      case .none, .adaptive: predictor = 0
      case .sub: predictor = left
      case .up: predictor = above
      case .paeth: predictor = paeth(left, above, upperLeft)
      }
      out[i] = row[i] &- predictor
    }
  }

  /// The PNG specification's Paeth predictor.
  static func paeth(_ a: UInt8, _ b: UInt8, _ c: UInt8) -> UInt8 {
    let p = Int(a) + Int(b) - Int(c)
    let pa = abs(p - Int(a))
    let pb = abs(p - Int(b))
    let pc = abs(p - Int(c))
    if pa <= pb && pa <= pc { return a }
    return pb <= pc ? b : c
  }
}

extension PNGFilter {
  /// The filter type byte that starts each row.
  var typeByte: UInt8 {
    switch self {
    case .none, .adaptive: 0
    case .sub: 1
    case .up: 2
    case .paeth: 4
    }
  }
}

extension Array where Element == UInt8 {
  mutating func appendBigEndian(_ value: UInt32) {
    append(UInt8(value >> 24))
    append(UInt8((value >> 16) & 0xFF))
    append(UInt8((value >> 8) & 0xFF))
    append(UInt8(value & 0xFF))
  }
}
