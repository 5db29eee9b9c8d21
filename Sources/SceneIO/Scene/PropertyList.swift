import SceneModel

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
    try checkDepth(bytes, file: file)
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
