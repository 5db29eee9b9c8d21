/// Portable float map: `Pf` (one channel) or `PF` (three), the size, then a
/// negative scale meaning little-endian, then 32-bit floats with the bottom
/// row first, as the format defines.
public enum PFMEncoder {
  public static func encode(_ image: RawImage<Float>) -> [UInt8] {
    precondition(image.channels == 1 || image.channels == 3)
    let magic = image.channels == 1 ? "Pf" : "PF"
    var bytes = Array("\(magic)\n\(image.width) \(image.height)\n-1.0\n".utf8)
    let rowLength = image.width * image.channels
    bytes.reserveCapacity(bytes.count + 4 * image.values.count)
    for row in stride(from: image.height - 1, through: 0, by: -1) {
      let start = row * rowLength
      for value in image.values[start..<(start + rowLength)] {
        withUnsafeBytes(of: value.bitPattern.littleEndian) {
          bytes.append(contentsOf: $0)
        }
      }
    }
    return bytes
  }
}
