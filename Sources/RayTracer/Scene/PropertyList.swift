#if canImport(FoundationEssentials)
import FoundationEssentials
#else
import Foundation
#endif

/// A property list read by the toolchain's Foundation decoder (XML or
/// binary, on Linux and macOS alike), as a tree of values.
enum PropertyList: Decodable, Sendable {
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

  init(from decoder: any Decoder) throws {
    let container = try decoder.singleValueContainer()
    if let value = try? container.decode(String.self) {
      self = .string(value)
    } else if let value = try? container.decode(Bool.self) {
      self = .boolean(value)
    } else if let value = try? container.decode(Double.self) {
      self = .number(value)
    } else if let value = try? container.decode([PropertyList].self) {
      self = .array(value)
    } else if let value = try? container.decode([String: PropertyList].self) {
      self = .dictionary(value)
    } else {
      self = .other
    }
  }

  /// Whether `bytes` hold a property list rather than the text format: a
  /// binary one (`bplist`), or XML (`<?xml`, `<!DOCTYPE plist`, `<plist`),
  /// after an optional byte-order mark and blanks. No text scene starts
  /// with `<`.
  static func recognises(_ bytes: UnsafeBufferPointer<UInt8>) -> Bool {
    if bytes.starts(with: Array("bplist".utf8)) { return true }
    var index = 0
    if bytes.starts(with: [0xEF, 0xBB, 0xBF]) { index = 3 }
    while index < bytes.count,
      [0x20, 0x09, 0x0A, 0x0D].contains(bytes[index])
    {
      index += 1
    }
    return index < bytes.count && bytes[index] == UInt8(ascii: "<")
  }

  /// Decodes `bytes`.
  ///
  /// - Throws: `SceneError` in `file`, at the decoder's line where it
  ///   gives one, for a file that is not a well-formed property list or is
  ///   nested deeper than `maximumDepth`.
  static func decode(
    _ bytes: [UInt8], file: String
  ) throws(SceneError) -> PropertyList {
    if let line = xmlLineBeyondDepth(bytes) {
      throw SceneError(
        file: file, line: line, column: 0,
        message: "the property list is nested more than \(maximumDepth) "
          + "levels deep")
    }
    do {
      return try PropertyListDecoder().decode(
        PropertyList.self, from: Data(bytes))
    } catch {
      let (line, reason) = describe(error)
      throw SceneError(
        file: file, line: line ?? 0, column: 0,
        message: "not a valid property list: \(reason)")
    }
  }

  /// The line of an XML property list at which its elements first nest
  /// deeper than `maximumDepth`, or nil. A conservative count of opening
  /// and closing `dict` and `array` tags; binary lists are not scanned.
  private static func xmlLineBeyondDepth(_ bytes: [UInt8]) -> Int? {
    guard !bytes.starts(with: Array("bplist".utf8)) else { return nil }
    var depth = 0
    var line = 1
    var index = 0
    let count = bytes.count
    while index < count {
      let byte = bytes[index]
      if byte == 0x0A {
        line += 1
      } else if byte == UInt8(ascii: "<"), index + 1 < count {
        let closing = bytes[index + 1] == UInt8(ascii: "/")
        let nameStart = index + (closing ? 2 : 1)
        if starts(bytes, at: nameStart, with: "dict")
          || starts(bytes, at: nameStart, with: "array")
        {
          var end = nameStart
          while end < count && bytes[end] != UInt8(ascii: ">") { end += 1 }
          let selfClosing = end > 0 && end < count
            && bytes[end - 1] == UInt8(ascii: "/")
          if closing {
            depth -= 1
          } else if !selfClosing {
            depth += 1
            if depth > maximumDepth { return line }
          }
        }
      }
      index += 1
    }
    return nil
  }

  private static func starts(
    _ bytes: [UInt8], at index: Int, with word: StaticString
  ) -> Bool {
    let length = word.utf8CodeUnitCount
    guard index + length <= bytes.count else { return false }
    return word.withUTF8Buffer { word in
      for offset in 0..<length where bytes[index + offset] != word[offset] {
        return false
      }
      return true
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
    var line: Int?
    let marker = " on line "
    if let last = reason.ranges(of: marker).last {
      let digits = reason[last.upperBound...].prefix { $0.isNumber }
      line = Int(digits)
    }
    // One line, whatever the decoder said.
    reason = reason.split(whereSeparator: \.isNewline).joined(separator: " ")
    if reason.hasSuffix(".") { reason.removeLast() }
    return (line, SceneParser.escaped(reason))
  }
}
