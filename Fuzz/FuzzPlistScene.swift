// libFuzzer harness for the property-list scene reader (`Fuzz/run.sh
// plist`).
//
// Each input is a scene file's bytes, read as `raytrace` reads a file: a
// property list when it looks like one (XML or binary), otherwise the text
// format, so the fuzzer crosses the boundary both ways. Whatever the bytes
// hold, the reader must return a scene or throw one well-formed error line,
// `fuzz.plist: error: …` (a key path or the file) or `fuzz.plist:LINE:
// error: …` (the decoder's line), free of control characters; a scene that
// reads must compile and render a 4x3 image. Anything else stops the
// fuzzer, which saves the input.

@testable import FastEngine
@testable import SceneIO
@testable import SceneModel

@_cdecl("LLVMFuzzerTestOneInput")
public func fuzzPlistScene(_ data: UnsafePointer<UInt8>?, _ size: Int) -> CInt {
  let bytes =
    data.map { Array(UnsafeBufferPointer(start: $0, count: size)) } ?? []
  let scene: Scene
  do throws(SceneError) {
    scene = try SceneReader.parse(bytes: bytes, file: "fuzz.plist")
  } catch {
    let description = error.description
    // Compared as bytes: a key starting with a combining mark joins the
    // space before it into one Character, which a Character comparison
    // would take for a missing " error: " (found by this fuzzer).
    guard isErrorLine(Array(description.utf8)),
      !description.unicodeScalars.contains(where: {
        $0.value < 0x20 || $0.value == 0x7F
      })
    else {
      fatalError(
        "fuzz invariant: malformed error \(description.debugDescription)")
    }
    return 0
  }
  let materials = scene.materials.count
  let all = scene.root.flattened()
  let indices =
    all.spheres.map(\.materialIndex) + all.planes.map(\.materialIndex)
    + all.triangles.map(\.materialIndex)
  guard indices.allSatisfy({ (0..<materials).contains($0) }) else {
    fatalError("fuzz invariant: a material index out of range")
  }
  let compiled = CompiledScene<StableKernel<Double>>(scene)
  let buffers = Renderer.render(
    compiled,
    settings: RenderSettings(
      width: 4, height: 3, outputs: [.depth, .normals, .shaded], threads: 1))
  guard buffers.depth.allSatisfy({ $0 == .infinity || ($0.isFinite && $0 > 0) })
  else { fatalError("fuzz invariant: a depth that is neither a miss nor > 0") }
  return 0
}

/// Whether `line` starts `fuzz.plist: error: `, `fuzz.plist:LINE: error: `
/// or `fuzz.plist:LINE:COLUMN: error: ` (the three forms of `SceneError`).
func isErrorLine(_ line: [UInt8]) -> Bool {
  let file = Array("fuzz.plist".utf8)
  guard line.starts(with: file) else { return false }
  var rest = line[file.count...]
  for _ in 0..<2 {
    guard rest.first == UInt8(ascii: ":") else { break }
    let digits = rest.dropFirst().prefix { (48...57).contains($0) }
    guard !digits.isEmpty else { break }
    rest = rest.dropFirst(1 + digits.count)
  }
  return rest.starts(with: Array(": error: ".utf8))
}
