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
//
// Inputs starting with 0xF1 or 0xF2 are not read as they are but as a
// program that builds a property list (`PlistRecipe`), so that the fuzzer
// mutates structure rather than bytes: an XML list of nested arrays and
// dictionaries, comments, CDATA sections, processing instructions,
// entities and numbers (in UTF-8, UTF-16 or UTF-32), or a binary list whose
// object table the bytes lay out, with shared references and counts of any
// size.

@testable import FastEngine
@testable import FastKernels
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport

@_cdecl("LLVMFuzzerTestOneInput")
public func fuzzPlistScene(_ data: UnsafePointer<UInt8>?, _ size: Int) -> CInt {
  let input =
    data.map { Array(UnsafeBufferPointer(start: $0, count: size)) } ?? []
  let bytes = PlistRecipe.build(input)
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

/// Property lists built from a fuzzer's bytes (see the header).
enum PlistRecipe {
  static func build(_ input: [UInt8]) -> [UInt8] {
    switch input.first {
    case 0xF1?: return xml(Array(input.dropFirst()))
    case 0xF2?: return binary(Array(input.dropFirst()))
    default: return input
    }
  }

  static let camera =
    "<key>Camera</key><dict><key>type</key><string>PerspectiveCamera</string>"
    + "<key>center</key><string>0 0 10</string><key>direction</key>"
    + "<string>0 0 -1</string><key>up</key><string>0 1 0</string>"
    + "<key>angle</key><string>30</string></dict>"

  /// An XML list: the first byte picks the encoding, each later one an
  /// element, a closing tag or a construct that holds none.
  static func xml(_ program: [UInt8]) -> [UInt8] {
    var text = "<?xml version=\"1.0\"?>\n<plist><dict>" + camera
      + "<key>Group</key><array>"
    var open: [String] = ["array"]
    var index = 1
    func next() -> UInt8 {
      defer { index += 1 }
      return index < program.count ? program[index] : 0
    }
    while index < program.count {
      let op = next()
      switch op % 16 {
      case 0:
        text += "<array>"
        open.append("array")
      case 1:
        text += "<dict><key>k\(next())</key>"
        open.append("dict")
      case 2:
        if let last = open.popLast() { text += "</\(last)>" }
      case 3: text += "</\(next() % 2 == 0 ? "array" : "dict")>"
      case 4:
        text += "<!-- " + String(repeating: "</array>", count: Int(next() % 8))
          + " -->"
      case 5:
        text += "<string><![CDATA[" + String(repeating: "</dict>", count: Int(next() % 8))
          + "]]></string>"
      case 6: text += "<?pi <array></array>?>"
      case 7: text += "<string>\(next()) \(next()) &amp; &lt;</string>"
      case 8:
        text += "<integer>" + String(repeating: "9", count: Int(next() % 40) + 1)
          + "</integer>"
      case 9: text += "<real>\(["1.5", "abc", "1e999", "-0", "nan"][Int(next() % 5)])</real>"
      case 10:
        text += "<dict><key>type</key><string>Sphere</string><key>center</key>"
          + "<string>0 0 \(next() % 5)</string><key>radius</key><string>1</string></dict>"
      case 11:
        let count = Int(next() % 32)
        text += String(repeating: "<array>", count: count)
        open += Array(repeating: "array", count: count)
      case 12: text += "\n"
      case 13: text += "<true/><false/><array/><dict/>"
      case 14: text += "<data>AAAA</data><date>2026-11-26T00:00:00Z</date>"
      default: text += String(decoding: [next(), next()], as: UTF8.self)
      }
    }
    while let last = open.popLast() { text += "</\(last)>" }
    text += "</dict></plist>\n"
    switch program.first.map({ $0 % 3 }) {
    case 1?:
      return [0xFF, 0xFE] + text.utf16.flatMap { [UInt8($0 & 0xFF), UInt8($0 >> 8)] }
    case 2?:
      return [0, 0, 0xFE, 0xFF] + text.unicodeScalars.flatMap { scalar in
        (0..<4).map { UInt8(truncatingIfNeeded: scalar.value >> (8 * (3 - $0))) }
      }
    default: return Array(text.utf8)
    }
  }

  /// A binary list: the bytes give the objects (kind, count, references)
  /// of a table with one-byte offsets and references, often shared.
  static func binary(_ program: [UInt8]) -> [UInt8] {
    var bytes = Array("bplist00".utf8)
    var offsets: [Int] = []
    var index = 0
    func next() -> UInt8 {
      defer { index += 1 }
      return index < program.count ? program[index] : 0
    }
    let objects = Int(next() % 60) + 1
    for object in 0..<objects {
      offsets.append(bytes.count)
      let kind = next() % 6
      switch kind {
      case 0, 1:
        // An array or a dictionary, its count short or written in full
        // (so it can claim far more than the file holds).
        let marker: UInt8 = kind == 0 ? 0xA0 : 0xD0
        let count = Int(next() % 4)
        if next() % 4 == 0 {
          bytes += [marker | 0x0F, 0x13]
          bytes += withUnsafeBytes(of: UInt64(next()) << UInt64(next() % 64)) {
            Array($0).reversed()
          }
        } else {
          bytes.append(marker | UInt8(count))
        }
        let references = kind == 1 ? 2 * count : count
        for _ in 0..<references {
          // Mostly later objects (a tree), sometimes any (shared, cycles).
          let target = next() % 8 == 0
            ? Int(next()) % objects : min(objects - 1, object + 1 + Int(next() % 3))
          bytes.append(UInt8(target))
        }
      case 2: bytes += [0x51, next()]
      case 3: bytes += [0x10, next()]
      case 4: bytes += [0x23] + (0..<8).map { _ in next() }
      default: bytes += [0x08]
      }
    }
    let table = bytes.count
    for offset in offsets { bytes.append(UInt8(truncatingIfNeeded: offset)) }
    bytes += [0, 0, 0, 0, 0, 0, 1, 1]
    for value in [objects, 0, table] {
      bytes += withUnsafeBytes(of: UInt64(value).bigEndian, Array.init)
    }
    return bytes
  }
}
