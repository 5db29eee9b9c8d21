import Geometry
import SceneDescription

/// The file formats an output can take, chosen by the path's extension.
package enum ImageFormat: String, CaseIterable, Sendable {
  /// 8-bit RGB, zlib-compressed.
  case png
  /// Binary P6, 8-bit RGB.
  case ppm
  /// Portable float map: 32-bit floats, little-endian, rows bottom to top.
  case pfm
  /// NumPy array of the raw values in the render's precision, row 0 on top.
  case npy

  /// Nil when the extension (case ignored) is none of the above.
  package init?(path: String) {
    guard let dot = path.lastIndex(of: "."),
      !path[path.index(after: dot)...].contains("/")
    else { return nil }
    self.init(rawValue: path[path.index(after: dot)...].lowercased())
  }

  /// PNG and PPM hold mapped 8-bit pixels; PFM and NPY the raw values.
  package var isEightBit: Bool { self == .png || self == .ppm }
}

/// Raw per-pixel values, `channels` per pixel, row 0 at the top.
package struct RawImage<Scalar: RayScalar>: Sendable {
  package let width: Int
  package let height: Int
  package let channels: Int
  package var values: [Scalar]

  package init(width: Int, height: Int, channels: Int, values: [Scalar]) {
    precondition(values.count == width * height * channels)
    self.width = width
    self.height = height
    self.channels = channels
    self.values = values
  }
}
