// libFuzzer harness for the BMP reader (`Fuzz/run.sh bmp`).
//
// Each input is a texture file's bytes. The reader must return an image of
// the size its header gives, whose every texel a lookup can read, or throw
// one `BMPReader.Failure` of one line. Anything else stops the fuzzer.

@testable import FastEngine
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport

@_cdecl("LLVMFuzzerTestOneInput")
public func fuzzBMPReader(_ data: UnsafePointer<UInt8>?, _ size: Int) -> CInt {
  let bytes =
    data.map { Array(UnsafeBufferPointer(start: $0, count: size)) } ?? []
  let image: Image8
  do throws(BMPReader.Failure) {
    image = try BMPReader.decode(bytes)
  } catch {
    guard !error.description.utf8.contains(UInt8(ascii: "\n")) else {
      fatalError("fuzz invariant: a message of several lines")
    }
    return 0
  }
  guard image.width > 0, image.height > 0,
    image.bytes.count == image.width * image.height * 3
  else { fatalError("fuzz invariant: an image of inconsistent size") }
  let texture = Texture(image: image)
  for (u, v) in [(0.0, 0.0), (1, 1), (0.5, 0.5), (-1, 2)] {
    _ = texture.color(at: TextureCoordinate<Double>(u, v))
  }
  return 0
}
