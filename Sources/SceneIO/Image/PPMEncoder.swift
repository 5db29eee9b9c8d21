import Geometry
import SceneDescription

/// Binary PPM (P6): a text header, then RGB bytes row by row from the top.
package enum PPMEncoder {
  package static func encode(_ image: Image8) -> [UInt8] {
    var bytes = Array("P6\n\(image.width) \(image.height)\n255\n".utf8)
    bytes.append(contentsOf: image.bytes)
    return bytes
  }
}
