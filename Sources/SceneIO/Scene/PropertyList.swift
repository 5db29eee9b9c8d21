import Geometry
import SceneDescription
import PlatformSupport

import Foundation

/// A property list read by the toolchain's Foundation decoder (XML or
/// binary, on Linux and macOS alike), as a tree of values.
enum PropertyList: Sendable {
  case string(String)
  case number(Double)
  case boolean(Bool)
  case array([PropertyList])
  case dictionary([String: PropertyList])
  /// Data or a date: nothing the scene schema uses.
  case other

  /// Deeper property lists are refused before they are decoded: the
  /// decoder recurses once per level, and no scene needs more than a few
  /// levels per group (`SceneParser.maximumGroupDepth` groups deep).
  static let maximumDepth = 4 * SceneParser.maximumGroupDepth + 16

  /// The tree of what Foundation's reader returns: strings, numbers,
  /// booleans, arrays and dictionaries (with string keys); anything else,
  /// data or a date, is `other`.
  ///
  /// Arrays and dictionaries are matched before numbers: asking whether a
  /// Swift array is an `NSNumber` bridges it, and everything in it, to
  /// Foundation's classes first, so every level of a deep list bridged all
  /// the levels below it again (2 MB of lists 300 deep took 13 s).
  init(_ value: Any) {
    switch value {
    case let string as String:
      self = .string(string)
    case let array as [Any]:
      self = .array(array.map(PropertyList.init))
    case let dictionary as [String: Any]:
      self = .dictionary(dictionary.mapValues(PropertyList.init))
    case let number as NSNumber:
      // A boolean is a Bool, or (on macOS) an NSNumber of a char's type.
      if type(of: value) == Bool.self
        || String(cString: number.objCType) == "c"
      {
        self = .boolean(number.boolValue)
      } else {
        self = .number(number.doubleValue)
      }
    default:
      self = .other
    }
  }

  /// Whether `bytes` hold a property list rather than the text format: a
  /// binary one (`bplist`), or XML (`<?xml`, `<!DOCTYPE plist`, `<plist`),
  /// after an optional byte-order mark and blanks. No text scene starts
  /// with `<`.
  static func recognises(_ bytes: UnsafeBufferPointer<UInt8>) -> Bool {
    if bytes.starts(with: Array("bplist".utf8)) { return true }
    // UTF-16 and UTF-32 with their byte-order marks, as Foundation reads
    // them: the first character after the mark is '<'.
    if wideEncoding(bytes) != nil { return true }
    var index = 0
    if bytes.starts(with: [0xEF, 0xBB, 0xBF]) { index = 3 }
    while index < bytes.count,
      [0x20, 0x09, 0x0A, 0x0D].contains(bytes[index])
    {
      index += 1
    }
    return index < bytes.count && bytes[index] == UInt8(ascii: "<")
  }

  /// The encoding of an XML property list in UTF-16 or UTF-32 with a
  /// byte-order mark whose first character is '<'; nil otherwise.
  static func wideEncoding(_ bytes: UnsafeBufferPointer<UInt8>)
    -> WideEncoding?
  {
    let marks: [([UInt8], WideEncoding)] = [
      ([0xFF, 0xFE, 0x00, 0x00, 0x3C, 0x00, 0x00, 0x00], .utf32LittleEndian),
      ([0x00, 0x00, 0xFE, 0xFF, 0x00, 0x00, 0x00, 0x3C], .utf32BigEndian),
      ([0xFF, 0xFE, 0x3C, 0x00], .utf16LittleEndian),
      ([0xFE, 0xFF, 0x00, 0x3C], .utf16BigEndian),
    ]
    return marks.first { bytes.starts(with: $0.0) }?.1
  }

  enum WideEncoding {
    case utf16LittleEndian, utf16BigEndian, utf32LittleEndian, utf32BigEndian
  }

  /// The text of a UTF-16 or UTF-32 file as UTF-8, without its mark, for
  /// the scan; nil when it is not valid in its encoding.
  static func utf8(_ bytes: [UInt8], from encoding: WideEncoding) -> [UInt8]? {
    let width =
      encoding == .utf16LittleEndian || encoding == .utf16BigEndian
      ? 2 : 4
    let little =
      encoding == .utf16LittleEndian || encoding == .utf32LittleEndian
    guard bytes.count % width == 0 else { return nil }
    var units: [UInt32] = []
    units.reserveCapacity(bytes.count / width - 1)
    for start in stride(from: width, to: bytes.count, by: width) {
      var unit: UInt32 = 0
      for offset in 0..<width {
        let byte = UInt32(bytes[start + (little ? width - 1 - offset : offset)])
        unit = unit << 8 | byte
      }
      units.append(unit)
    }
    var text = ""
    if width == 2 {
      var decoder = UTF16()
      var iterator = units.map { UInt16(truncatingIfNeeded: $0) }.makeIterator()
      loop: while true {
        switch decoder.decode(&iterator) {
        case .scalarValue(let scalar): text.unicodeScalars.append(scalar)
        case .emptyInput: break loop
        case .error: return nil
        }
      }
    } else {
      for unit in units {
        guard let scalar = Unicode.Scalar(unit) else { return nil }
        text.unicodeScalars.append(scalar)
      }
    }
    return Array(text.utf8)
  }

  /// `text` with its XML declaration's encoding, if it names one, made
  /// UTF-8, as the text now is.
  static func declaringUTF8(_ text: [UInt8]) -> [UInt8] {
    let string = String(decoding: text, as: UTF8.self)
    guard string.hasPrefix("<?xml"), let end = string.firstRange(of: "?>"),
      let attribute = string[..<end.lowerBound].firstRange(of: "encoding=")
    else { return text }
    let valueStart = attribute.upperBound
    guard valueStart < end.lowerBound else { return text }
    let quote = string[valueStart]
    guard quote == "\"" || quote == "'",
      let valueEnd = string[string.index(after: valueStart)..<end.lowerBound]
        .firstIndex(of: quote)
    else { return text }
    return Array(
      (string[..<valueStart] + "\"UTF-8\""
        + string[string.index(after: valueEnd)...]).utf8)
  }

  /// Decodes `bytes`.
  ///
  /// - Throws: `SceneError` in `file`, at the line of the problem, for a
  ///   file that is not a well-formed property list, is nested deeper than
  ///   `maximumDepth`, or whose shared references would make the decoder
  ///   visit more than `maximumVisits(forSize:)` objects.
  static func decode(
    _ bytes: [UInt8], file: String
  ) throws(SceneError) -> PropertyList {
    try check(bytes, file: file)
    // UTF-16 and UTF-32 are decoded as UTF-8: Foundation on Linux reads
    // no UTF-32 (macOS reads both), and then every platform reads both.
    var decodable = bytes
    if let encoding = bytes.withUnsafeBufferPointer(wideEncoding),
      let utf8 = utf8(bytes, from: encoding)
    {
      decodable = declaringUTF8(utf8)
    }
    do {
      // The untyped reader: the typed decoder (`Decodable`) builds a
      // coding path for every value it tries, and took a hundred times as
      // long on deep lists (its retains and releases were 80 % of a run).
      let value = try PropertyListSerialization.propertyList(
        from: Data(decodable), options: [], format: nil)
      return PropertyList(value)
    } catch {
      let (line, reason) = describe(error)
      throw SceneError(
        file: file, line: line ?? 0, column: 0,
        message: "not a valid property list: \(reason)")
    }
  }

  /// The decoder's own explanation, and its line when it names one
  /// ("… on line 12").
  private static func describe(_ error: any Error) -> (Int?, String) {
    var reason = "the decoder could not read it"
    if case DecodingError.dataCorrupted(let context) = error {
      reason = context.debugDescription
      if let underlying = context.underlyingError as? CocoaError,
        let detail = underlying.userInfo["NSDebugDescription"] as? String
      {
        reason = detail
      }
    }
    // The decoder's line is not always the problem's (it said line 1 for
    // a wrong tag on line 22): the scan before decoding finds every
    // problem of the file's structure at its line, so what reaches here
    // is named without one.
    let line: Int? = nil
    // One line, whatever the decoder said.
    reason = reason.split(whereSeparator: \.isNewline).joined(separator: " ")
    if reason.hasSuffix(".") { reason.removeLast() }
    return (line, SceneParser.escaped(reason))
  }
}
