import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// Property lists made to hurt the reader: counts that overflow, nesting
/// hidden from a naive scan, shared references that expand exponentially,
/// wrong lines and wrong reasons, wide encodings. Each is one line and
/// exit status 1, never a trap or a hang.
final class PlistHostileTests: XCTestCase {
  func message(_ bytes: [UInt8], file: String = "h.plist") -> String {
    do {
      _ = try SceneReader.parse(bytes: bytes, file: file)
      return "read"
    } catch {
      return error.description
    }
  }

  /// The trailer of a binary list: offset and reference sizes, object
  /// count, top object, table offset.
  func trailer(objects: Int, tableOffset: Int) -> [UInt8] {
    var bytes = [UInt8](repeating: 0, count: 6) + [1, 1]
    for value in [objects, 0, tableOffset] {
      bytes += withUnsafeBytes(of: UInt64(value).bigEndian, Array.init)
    }
    return bytes
  }

  /// A binary list of `objects`, the first the top, with one-byte offsets
  /// and references.
  func list(_ objects: [[UInt8]]) -> [UInt8] {
    var bytes = Array("bplist00".utf8)
    var offsets: [UInt8] = []
    for object in objects {
      offsets.append(UInt8(bytes.count))
      bytes += object
    }
    let table = bytes.count
    return bytes + offsets + trailer(objects: objects.count, tableOffset: table)
  }

  /// A dictionary claiming 2⁶² entries: the count is refused before it is
  /// doubled into keys and values (it overflowed, a trap).
  func testBinary_CountOfTwoToTheSixtyTwo() {
    var bytes = Array("bplist00".utf8) + [0xDF, 0x13]
    bytes += withUnsafeBytes(of: (UInt64(1) << 62).bigEndian, Array.init)
    let table = bytes.count
    bytes += [8] + trailer(objects: 1, tableOffset: table)
    XCTAssertEqual(
      message(bytes),
      "h.plist: error: not a valid property list: the binary object table "
        + "is malformed")
  }

  /// Sixty arrays, each listing the next twice: 475 bytes in the issue's
  /// form, 2⁶⁰ objects for a decoder that reads each reference again.
  func testBinary_SharedReferencesExpandingExponentially() {
    var objects: [[UInt8]] = (0..<60).map {
      [0xA2, UInt8($0 + 1), UInt8($0 + 1)]
    }
    objects.append([0x51, UInt8(ascii: "x")])
    let bytes = list(objects)
    let start = Date()
    XCTAssertTrue(
      message(bytes).hasSuffix(
        "the property list's shared objects would be read more than "
          + "\(PropertyList.maximumVisits(forSize: bytes.count)) times (each "
          + "reference to an object reads it again)"), message(bytes))
    XCTAssertLessThan(Date().timeIntervalSince(start), 1)
    // Sharing within the bound is read.
    XCTAssertEqual(PropertyList.binaryShape(bytes)?.visits, 1 << 60)
  }

  /// Closing tags inside a comment or a CDATA section close nothing: the
  /// nesting is measured as the decoder reads it.
  func testXML_NestingHiddenInCommentsAndCDATA() {
    let opening = String(repeating: "<array>", count: 100_000)
    let closing = String(repeating: "</array>", count: 100_000)
    for hidden in [
      "<!-- \(closing) -->", "<string><![CDATA[\(closing)]]></string>",
    ] {
      let text =
        "<?xml version=\"1.0\"?>\n<plist>\n\(opening)\(hidden)\n</plist>\n"
      XCTAssertEqual(
        message(Array(text.utf8)),
        "h.plist:3: error: the property list is nested more than 816 levels "
          + "deep")
    }
    // Tags in comments, processing instructions and the document type do
    // not count either way.
    let fine = """
      <?xml version="1.0"?>
      <!DOCTYPE plist PUBLIC "-//Apple//DTD PLIST 1.0//EN" \
      "http://www.apple.com/DTDs/PropertyList-1.0.dtd">
      <?target <array><array>?>
      <plist><!-- </dict> <array> --><dict>
      <key>Group</key><array/></dict></plist>
      """
    XCTAssertEqual(
      message(Array(fine.utf8)), "h.plist: error: the scene has no Camera")
  }

  /// The line of the problem, not the decoder's line 1.
  func testXML_ErrorsAtTheirLine() {
    var lines = Array(repeating: "<!-- a line -->", count: 20)
    lines.insert("<?xml version=\"1.0\"?>\n<plist><dict>", at: 0)
    let before = lines.joined(separator: "\n")
    func at(_ line: String) -> String {
      message(Array((before + "\n" + line + "\n</dict></plist>\n").utf8))
    }
    XCTAssertEqual(
      at("<key>a</key><strin>x</string>"),
      "h.plist:23: error: not a valid property list: <strin> is not an "
        + "element of a property list")
    XCTAssertEqual(
      at("<key>a</key><string>x</array>"),
      "h.plist:23: error: not a valid property list: </array> closes "
        + "<string> of line 23")
    XCTAssertEqual(
      message(Array("<?xml version=\"1.0\"?>\n<plist>\n<dict>\n".utf8)),
      "h.plist:3: error: not a valid property list: <dict> is never closed "
        + "(the file ends first)")
    XCTAssertEqual(
      message(Array("<plist>\n<!-- open\n".utf8)),
      "h.plist:2: error: not a valid property list: a comment is never closed")
  }

  /// Numbers that are not: too large for any integer, or not a number.
  func testXML_NumbersThatAreNot() {
    func value(_ element: String) -> String {
      message(
        Array(
          ("<?xml version=\"1.0\"?>\n<plist><dict>\n<key>Group</key>"
            + "\(element)</dict></plist>").utf8))
    }
    XCTAssertEqual(
      value("<integer>99999999999999999999999</integer>"),
      "h.plist:3: error: not a valid property list: "
        + "<integer>99999999999999999999999</integer> is too large for any "
        + "integer type (64 bits)")
    XCTAssertEqual(
      value("<real>abc</real>"),
      "h.plist:3: error: not a valid property list: <real>abc</real> is not "
        + "a number")
    XCTAssertEqual(
      value("<integer>1.5</integer>"),
      "h.plist:3: error: not a valid property list: <integer>1.5</integer> "
        + "is not a whole number")
  }

  /// UTF-16 and UTF-32, either byte order, with their byte-order marks:
  /// read as the UTF-8 file they spell.
  func testWideEncodings() throws {
    let text = """
      <?xml version="1.0" encoding="UTF-16"?>
      <plist><dict>
      <key>Camera</key><dict><key>type</key><string>PerspectiveCamera</string>
      <key>center</key><string>0 0 10</string>
      <key>direction</key><string>0 0 -1</string>
      <key>up</key><string>0 1 0</string><key>angle</key><string>30</string>\
      </dict>
      <key>Group</key><array><dict><key>type</key><string>Sphere</string>
      <key>center</key><string>0 0 0</string><key>radius</key>\
      <string>2</string></dict></array>
      </dict></plist>
      """
    let utf8 = try SceneReader.parse(
      bytes: Array(text.replacingOccurrences(of: "UTF-16", with: "UTF-8").utf8),
      file: "u.plist")
    let scalars = text.unicodeScalars.map(\.value)
    func encoded(width: Int, little: Bool) -> [UInt8] {
      var units: [UInt32] = [0xFEFF]
      if width == 2 {
        units += text.utf16.map(UInt32.init)
      } else {
        units += scalars
      }
      var bytes: [UInt8] = []
      for unit in units {
        var unitBytes = (0..<width).map {
          UInt8(truncatingIfNeeded: unit >> (8 * UInt32(width - 1 - $0)))
        }
        if little { unitBytes.reverse() }
        bytes += unitBytes
      }
      return bytes
    }
    for (width, little) in [(2, true), (2, false), (4, true), (4, false)] {
      let bytes = encoded(width: width, little: little)
      let scene = try SceneReader.parse(bytes: bytes, file: "w.plist")
      XCTAssertEqual(
        scene.root, utf8.root, "UTF-\(8 * width) \(little ? "LE" : "BE")")
      XCTAssertEqual(scene.camera, utf8.camera)
    }
    XCTAssertEqual(
      message([0xFF, 0xFE, 0x3C, 0x00, 0x00, 0xD8, 0x41]),
      "h.plist: error: not a valid property list: its text is not valid in "
        + "the encoding its byte-order mark names")
  }

  /// Values of every kind keep their kind: a boolean is not read as a
  /// number, an integer or a real is a number, data and dates are other.
  func testValueKinds() {
    func message(_ value: String) -> String {
      self.message(
        Array(
          ("<?xml version=\"1.0\"?>\n<plist><dict><key>Camera</key>\(value)"
            + "</dict></plist>").utf8))
    }
    XCTAssertTrue(
      message("<true/>").hasSuffix("found a boolean"), message("<true/>"))
    XCTAssertTrue(message("<integer>3</integer>").hasSuffix("found a number"))
    XCTAssertTrue(message("<real>2.5</real>").hasSuffix("found a number"))
    XCTAssertTrue(
      message("<data>AAAA</data>").hasSuffix("found data or a date"))
    XCTAssertTrue(
      message("<string>x</string>").hasSuffix("found the string \"x\""))
    XCTAssertTrue(message("<array/>").hasSuffix("found an array"))
  }

  /// Lists and dictionaries 300 deep, under the 816-level limit, read to
  /// the bottom with every level's kind. (Before arrays were matched ahead
  /// of numbers, each level bridged all those below it again: 2 MB of such
  /// lists took 5–21 s, docs/ROBUSTNESS.md; here the shape is what is
  /// checked, not the time.)
  func testXML_DeepListsKeepTheirShape() throws {
    let depth = 300
    let arrays =
      String(repeating: "<array>", count: depth) + "<true/>"
      + String(repeating: "</array>", count: depth)
    let dictionaries =
      String(repeating: "<dict><key>k</key>", count: depth)
      + "<integer>7</integer>" + String(repeating: "</dict>", count: depth)
    let text =
      "<?xml version=\"1.0\"?>\n<plist><array>"
      + String(repeating: arrays + dictionaries, count: 3) + "</array></plist>"
    let root = try PropertyList.decode(Array(text.utf8), file: "h.plist")
    guard case .array(let chains) = root else {
      return XCTFail("\(root)")
    }
    XCTAssertEqual(chains.count, 6)
    for (index, chain) in chains.enumerated() {
      var node = chain
      for _ in 0..<depth {
        switch node {
        case .array(let items) where items.count == 1: node = items[0]
        case .dictionary(let items) where items.count == 1:
          node = items["k"] ?? .other
        default: return XCTFail("chain \(index): \(node)")
        }
      }
      switch (index % 2, node) {
      case (0, .boolean(true)), (1, .number(7)): break
      default: XCTFail("chain \(index) ends in \(node)")
      }
    }
  }

  /// Found by the fuzzer: a binary list holding a set made Foundation's
  /// reader crash in its bridging (SIGSEGV); so would a dictionary with a
  /// key that is not a string. Both are refused before it sees them.
  func testBinary_SetsAndKeysThatAreNotStrings() {
    // A set of two arrays.
    let set = list([[0xC2, 1, 2], [0xA0], [0xA0]])
    XCTAssertEqual(
      message(set),
      "h.plist: error: not a valid property list: it holds a set, which no "
        + "scene holds")
    // A dictionary whose key is an array.
    let key = list([[0xD1, 1, 2], [0xA0], [0x51, UInt8(ascii: "x")]])
    XCTAssertEqual(
      message(key),
      "h.plist: error: not a valid property list: a dictionary has a key "
        + "that is not a string")
    // The fuzzer's own input replays to one line.
    let finding = "\(projectFolder)/Fuzz/corpus/plist/finding-set-bridging"
    let bytes =
      (try? Data(contentsOf: URL(fileURLWithPath: finding))).map(Array.init)
      ?? []
    XCTAssertFalse(bytes.isEmpty)
    XCTAssertTrue(message(bytes).hasPrefix("h.plist: error: "), message(bytes))
  }
}

private let projectFolder = ProjectFiles.projectFolder

extension PropertyList {
  /// A binary list's depth and visits, nil when it is refused.
  static func binaryShape(_ bytes: [UInt8]) -> (depth: Int, visits: Int)? {
    guard case .shape(let depth, let visits) = binaryReading(bytes)
    else { return nil }
    return (depth, visits)
  }
}
