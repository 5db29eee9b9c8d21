import Geometry
import SceneDescription
import PlatformSupport

#if canImport(FoundationEssentials)
  import FoundationEssentials
#else
  import Foundation
#endif

/// The values of a property-list scene: numbers, vectors and colours as
/// the course writes them, each checked at its key path.
extension PlistSceneBuilder {
  // MARK: - Values

  /// The file a resource NAME names, as the course's loader finds it
  /// (`ResourceLookup`).
  func resource(
    _ name: String, folder: String, fileExtension: String, _ path: String
  ) throws(SceneError) -> String {
    let candidates = ResourceLookup.candidates(
      name, folder: folder, fileExtension: fileExtension, besideScene: file)
    if let found = ResourceLookup.existing(candidates) { return found }
    throw fail(
      path,
      "no file for \(quoted(.string(name))); tried "
        + candidates.map { "'\(SceneParser.escaped($0))'" }
        .joined(separator: ", "))
  }

  func materialIndex(
    _ fields: [String: PropertyList], _ path: String
  ) throws(SceneError) -> Int? {
    guard let index = try number(fields, "materialIndex", path) else {
      return nil
    }
    let available = max(materials.count, 1)
    guard index >= 0, index == index.rounded(), index < Double(available)
    else {
      throw fail(
        "\(path).materialIndex",
        "materialIndex \(quoted(fields["materialIndex"])) is out of range: "
          + (materials.isEmpty
            ? "the scene has no materials (only the default, 0)"
            : "the scene has \(materials.count) material"
              + "\(materials.count == 1 ? "" : "s") "
              + "(0 to \(materials.count - 1))")
      )
    }
    return Int(index)
  }

  func checkDepth(_ depth: Int, _ path: String) throws(SceneError) {
    guard depth < SceneParser.maximumGroupDepth else {
      throw fail(
        path,
        "Groups and Transforms are nested more than "
          + "\(SceneParser.maximumGroupDepth) deep")
    }
  }

  /// The `type` string, which must be one of `choices` (or absent when not
  /// `required`, giving the first choice).
  @discardableResult
  func checkType(
    _ fields: [String: PropertyList], _ choices: [String], _ path: String,
    required: Bool
  ) throws(SceneError) -> String {
    guard let type = try string(fields, "type", path) else {
      if required {
        throw fail(
          path,
          "missing 'type' (one of \(choices.joined(separator: ", ")))")
      }
      return choices[0]
    }
    guard choices.contains(type) else {
      let hint =
        nearest(to: type, in: choices)
        .map { "; did you mean '\($0)'?" } ?? ""
      throw fail(
        "\(path).type",
        "unknown type \(quoted(.string(type))); expected "
          + choices.joined(separator: ", ") + hint)
    }
    return type
  }

  func checkKeys(
    _ fields: [String: PropertyList], _ allowed: [String], _ path: String
  ) throws(SceneError) {
    for key in fields.keys.sorted() where !allowed.contains(key) {
      let hint =
        nearest(to: key, in: allowed)
        .map { "; did you mean '\($0)'?" } ?? ""
      throw fail(
        path.isEmpty
          ? SceneParser.escaped(key) : "\(path).\(SceneParser.escaped(key))",
        "unknown key; expected "
          + allowed.joined(separator: ", ") + hint)
    }
  }

  func dictionary(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> [String: PropertyList] {
    guard case .dictionary(let fields) = value else {
      throw fail(path, "expected a dictionary, found \(kind(value))")
    }
    return fields
  }

  func array(
    _ value: PropertyList, _ path: String
  ) throws(SceneError) -> [PropertyList] {
    guard case .array(let items) = value else {
      throw fail(path, "expected an array, found \(kind(value))")
    }
    return items
  }

  func string(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> String? {
    guard let value = fields[key] else { return nil }
    guard case .string(let text) = value, !text.isEmpty else {
      throw fail("\(path).\(key)", "expected a name, found \(quoted(value))")
    }
    return text
  }

  func number(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> Double? {
    guard let value = fields[key] else { return nil }
    if case .number(let number) = value {
      guard number.isFinite else {
        throw fail("\(path).\(key)", "expected a finite number")
      }
      try checkRange(number, "\(number)", "\(path).\(key)")
      return number
    }
    return try numbers(value, count: 1, "\(path).\(key)")[0]
  }

  func vector(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> Vector3<Double>? {
    guard let value = fields[key] else { return nil }
    let numbers = try self.numbers(value, count: 3, "\(path).\(key)")
    return Vector3(numbers[0], numbers[1], numbers[2])
  }

  func color(
    _ fields: [String: PropertyList], _ key: String, _ path: String
  ) throws(SceneError) -> RGB<Double>? {
    guard let value = try vector(fields, key, path) else { return nil }
    guard value.x >= 0 && value.y >= 0 && value.z >= 0 else {
      throw fail("\(path).\(key)", "'\(key)' components must not be negative")
    }
    return value
  }

  func numbers(
    _ value: PropertyList, count: Int, _ path: String
  ) throws(SceneError) -> [Double] {
    guard case .string(let text) = value else {
      if count == 1, case .number(let number) = value, number.isFinite {
        try checkRange(number, "\(number)", path)
        return [number]
      }
      throw fail(
        path,
        "expected \(count == 1 ? "a number" : "\(count) numbers") in a "
          + "string, found \(quoted(value))")
    }
    return try numbers(text, count: count, path, what: "expected")
  }

  /// Exactly `count` finite decimal numbers separated by blanks, each read
  /// as the text format reads numbers (correctly rounded).
  func numbers(
    _ text: String, count: Int, _ path: String, what: String
  ) throws(SceneError) -> [Double] {
    let words = text.split(whereSeparator: \.isWhitespace)
    var values: [Double] = []
    for word in words {
      var utf8 = Array(word.utf8)
      let value = utf8.withUnsafeMutableBufferPointer {
        DecimalParser.parse(UnsafeBufferPointer($0))
      }
      if let value, NumberRange.isDecimal(String(word)) {
        try checkRange(value, String(word), path)
      }
      guard let value, value.isFinite else { values = []; break }
      values.append(value)
    }
    guard values.count == count, words.count == count else {
      let noun = count == 1 ? "1 number" : "\(count) numbers"
      let found =
        words.count == values.count || values.isEmpty && words.isEmpty
        ? "" : " (finite, decimal)"
      throw fail(
        path, "\(what) \(noun)\(found), found \(quoted(.string(text)))")
    }
    return values
  }

  /// Refuses a number, written `text`, that the render's precision
  /// cannot hold (see `NumberRange.rangeProblem`), at its key path.
  func checkRange(
    _ value: Double, _ text: String, _ path: String
  ) throws(SceneError) {
    guard !options.precision.holds(value),
      let problem = options.precision.rangeProblem(value, text: text)
    else { return }
    throw fail(path, problem).exceeding(options.precision)
  }

  func required<T>(
    _ value: T?, _ key: String, _ path: String
  ) throws(SceneError) -> T {
    guard let value else {
      throw fail(path, "missing '\(key)'")
    }
    return value
  }

  func kind(_ value: PropertyList) -> String {
    switch value {
    case .string(let text): "the string \(quoted(.string(text)))"
    case .number: "a number"
    case .boolean: "a boolean"
    case .array: "an array"
    case .dictionary: "a dictionary"
    case .other: "data or a date"
    }
  }

  /// A value as a message quotes it: strings in double quotes, escaped and
  /// cut to 48 characters.
  func quoted(_ value: PropertyList?) -> String {
    guard let value else { return "nothing" }
    switch value {
    case .string(let text):
      let cut = text.count > 48 ? String(text.prefix(48)) + "…" : text
      return "\"\(SceneParser.escaped(cut))\""
    case .number(let number): return "\(number)"
    default: return kind(value)
    }
  }

  func fail(_ path: String, _ message: String) -> SceneError {
    SceneError(
      file: SceneParser.escaped(file), line: 0, column: 0,
      message: path.isEmpty ? message : "\(path): \(message)")
  }
}
