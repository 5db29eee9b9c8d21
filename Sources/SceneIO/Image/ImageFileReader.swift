import Geometry
import SceneDescription
import PlatformSupport

/// An image read back for comparison (`raytrace compare`): 8-bit RGB
/// pixels, or raw values (1 or 3 channels) as the float formats hold them.
package struct ReadImage: Sendable, Equatable {
  package var width: Int
  package var height: Int
  package var channels: Int
  /// Row 0 at the top, `channels` values a pixel: 0…255 for 8-bit images.
  package var values: [Double]
  /// PNG, PPM, BMP (levels) rather than PFM, NPY (raw values).
  package var isEightBit: Bool

  package init(
    width: Int, height: Int, channels: Int, values: [Double],
    isEightBit: Bool
  ) {
    precondition(values.count == width * height * channels)
    self.width = width
    self.height = height
    self.channels = channels
    self.values = values
    self.isEightBit = isEightBit
  }

  package init(_ image: Image8) {
    self.init(
      width: image.width, height: image.height, channels: 3,
      values: image.bytes.map(Double.init), isEightBit: true)
  }

  /// The value of `channel` at (`column`, `row`).
  package subscript(column: Int, row: Int, channel: Int) -> Double {
    values[(row * width + column) * channels + channel]
  }
}

/// Reads the image formats the project writes (PNG, PPM, PFM, NPY) and BMP,
/// recognised by their content.
package enum ImageFileReader {
  package struct Failure: Error, Equatable, CustomStringConvertible {
    package var description: String
    init(_ description: String) { self.description = description }
  }

  /// The largest side accepted, as for the render's own images.
  package static let maximumSide = 1 << 15

  /// Refuses an image whose values (a Double each) would not fit in what
  /// the process may use, before they are allocated.
  static func checkRoom(_ count: Int) throws(Failure) {
    let bytes = Double(count) * 8
    guard let limit = Memory.limits().first, bytes > Double(limit.bytes) / 4
    else { return }
    throw Failure(
      "its \(count) values would need \(Int(bytes / 1_048_576)) MiB, more "
        + "than a quarter of what the process may use (\(limit.what))")
  }

  /// The image in the file at `path` (a regular file, read whole).
  package static func read(contentsOf path: String) throws(Failure)
    -> ReadImage
  {
    let bytes: [UInt8]
    do { bytes = try readFile(path) } catch { throw Failure(error.reason) }
    return try read(bytes)
  }

  package static func read(_ bytes: [UInt8]) throws(Failure) -> ReadImage {
    func starts(with prefix: [UInt8]) -> Bool {
      bytes.count >= prefix.count && Array(bytes.prefix(prefix.count)) == prefix
    }
    if starts(with: [0x89, 0x50, 0x4E, 0x47]) {
      do { return ReadImage(try PNGDecoder.decode(bytes)) } catch {
        throw Failure("not a PNG file it can read: \(error.description)")
      }
    }
    if starts(with: Array("BM".utf8)) {
      do { return ReadImage(try BMPReader.decode(bytes)) } catch {
        throw Failure("not a BMP file it can read: \(error.description)")
      }
    }
    if starts(with: Array("P6".utf8)) { return try ppm(bytes) }
    if starts(with: Array("PF".utf8)) || starts(with: Array("Pf".utf8)) {
      return try pfm(bytes)
    }
    if starts(with: [0x93] + Array("NUMPY".utf8)) { return try npy(bytes) }
    throw Failure("not an image in a format it reads (PNG, PPM, PFM, NPY, BMP)")
  }

  /// The header's whitespace-separated words after the magic, and where
  /// the data starts (one whitespace byte after the last word).
  private static func headerWords(_ bytes: [UInt8], count: Int)
    throws(Failure) -> (words: [String], data: Int)
  {
    var words: [String] = []
    var index = 2
    while words.count < count {
      while index < bytes.count, isSpace(bytes[index]) { index += 1 }
      var word: [UInt8] = []
      while index < bytes.count, !isSpace(bytes[index]), word.count < 32 {
        word.append(bytes[index])
        index += 1
      }
      guard !word.isEmpty else { throw Failure("its header ends early") }
      words.append(String(decoding: word, as: UTF8.self))
    }
    guard index < bytes.count else { throw Failure("it holds no pixels") }
    return (words, index + 1)
  }

  private static func isSpace(_ byte: UInt8) -> Bool {
    byte == 0x20 || byte == 0x0A || byte == 0x0D || byte == 0x09
  }

  private static func size(_ width: String, _ height: String)
    throws(Failure) -> (Int, Int)
  {
    guard let w = Int(width), let h = Int(height), w >= 1, h >= 1,
      w <= maximumSide, h <= maximumSide
    else {
      throw Failure(
        "its size '\(width) \(height)' is not two whole numbers from 1 to "
          + "\(maximumSide)")
    }
    return (w, h)
  }

  /// Binary PPM, 8 bits a channel.
  private static func ppm(_ bytes: [UInt8]) throws(Failure) -> ReadImage {
    let (words, data) = try headerWords(bytes, count: 3)
    let (width, height) = try size(words[0], words[1])
    guard words[2] == "255" else {
      throw Failure("its largest value is \(words[2]), not 255")
    }
    let count = width * height * 3
    guard bytes.count - data >= count else {
      throw Failure(
        "it holds \(bytes.count - data) bytes of pixels, not \(count)")
    }
    try checkRoom(count)
    return ReadImage(
      width: width, height: height, channels: 3,
      values: bytes[data..<data + count].map(Double.init), isEightBit: true)
  }

  /// Portable float map: 32-bit floats, rows from the bottom; a negative
  /// scale means little-endian.
  private static func pfm(_ bytes: [UInt8]) throws(Failure) -> ReadImage {
    let channels = bytes[1] == UInt8(ascii: "F") ? 3 : 1
    let (words, data) = try headerWords(bytes, count: 3)
    let (width, height) = try size(words[0], words[1])
    guard let scale = Double(words[2]), scale != 0, scale.isFinite else {
      throw Failure("its scale '\(words[2])' is not a non-zero number")
    }
    let count = width * height * channels
    guard bytes.count - data >= 4 * count else {
      throw Failure(
        "it holds \(bytes.count - data) bytes of values, not \(4 * count)")
    }
    try checkRoom(count)
    var values = [Double](repeating: 0, count: count)
    for row in 0..<height {
      for index in 0..<width * channels {
        let offset = data + 4 * ((height - 1 - row) * width * channels + index)
        var bits: UInt32 = 0
        for byte in 0..<4 {
          bits |= UInt32(bytes[offset + byte]) << (8 * UInt32(byte))
        }
        if scale > 0 { bits = bits.byteSwapped }
        values[row * width * channels + index] = Double(
          Float(bitPattern: bits))
      }
    }
    return ReadImage(
      width: width, height: height, channels: channels, values: values,
      isEightBit: false)
  }

  /// NumPy's `.npy`, version 1 or 2: `<f4` or `<f8`, C order, shape H×W or
  /// H×W×C with C of 1 or 3.
  private static func npy(_ bytes: [UInt8]) throws(Failure) -> ReadImage {
    guard bytes.count >= 10 else { throw Failure("its header ends early") }
    let major = bytes[6]
    let lengthBytes = major == 1 ? 2 : 4
    guard major == 1 || major == 2, bytes.count >= 8 + lengthBytes else {
      throw Failure("its version \(major) is not 1 or 2")
    }
    var length = 0
    for index in 0..<lengthBytes {
      length |= Int(bytes[8 + index]) << (8 * index)
    }
    let data = 8 + lengthBytes + length
    guard bytes.count >= data else { throw Failure("its header ends early") }
    let header = String(
      decoding: bytes[(8 + lengthBytes)..<data], as: UTF8.self)
    let bytesPerValue: Int
    if header.contains("'<f4'") {
      bytesPerValue = 4
    } else if header.contains("'<f8'") {
      bytesPerValue = 8
    } else {
      throw Failure("its values are not little-endian '<f4' or '<f8'")
    }
    guard header.contains("'fortran_order': False"),
      let open = header.firstIndex(of: "("),
      let close = header[open...].firstIndex(of: ")")
    else { throw Failure("its shape is not given in C order") }
    let dimensions = header[header.index(after: open)..<close]
      .split(separator: ",").map {
        Int($0.filter { !$0.isWhitespace })
      }
    guard dimensions.count == 2 || dimensions.count == 3,
      dimensions.allSatisfy({ $0 != nil })
    else { throw Failure("its shape is not H×W or H×W×C") }
    let channels = dimensions.count == 3 ? dimensions[2] ?? 0 : 1
    guard channels == 1 || channels == 3 else {
      throw Failure("it has \(channels) channels, not 1 or 3")
    }
    let (width, height) = try size(
      String(dimensions[1] ?? 0), String(dimensions[0] ?? 0))
    let count = width * height * channels
    guard bytes.count - data >= bytesPerValue * count else {
      throw Failure(
        "it holds \(bytes.count - data) bytes of values, not "
          + "\(bytesPerValue * count)")
    }
    try checkRoom(count)
    var values = [Double](repeating: 0, count: count)
    for index in 0..<count {
      var bits: UInt64 = 0
      for byte in 0..<bytesPerValue {
        let offset = data + bytesPerValue * index + byte
        bits |= UInt64(bytes[offset]) << (8 * UInt64(byte))
      }
      values[index] =
        bytesPerValue == 4
        ? Double(Float(bitPattern: UInt32(truncatingIfNeeded: bits)))
        : Double(bitPattern: bits)
    }
    return ReadImage(
      width: width, height: height, channels: channels, values: values,
      isEightBit: false)
  }
}
