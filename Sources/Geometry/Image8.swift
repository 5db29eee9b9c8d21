/// An 8-bit RGB image, row 0 at the top, three bytes per pixel.
public struct Image8: Hashable, Sendable {
  public let width: Int
  public let height: Int
  public var bytes: [UInt8]

  public init(width: Int, height: Int, bytes: [UInt8]) {
    precondition(bytes.count == width * height * 3)
    self.width = width
    self.height = height
    self.bytes = bytes
  }

  /// The (r, g, b) of the pixel in `column`, `row`.
  public subscript(column: Int, row: Int) -> (UInt8, UInt8, UInt8) {
    let index = 3 * (row * width + column)
    return (bytes[index], bytes[index + 1], bytes[index + 2])
  }
}
