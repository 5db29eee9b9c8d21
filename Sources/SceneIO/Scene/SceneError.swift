import SceneModel

/// A problem with a scene file, reported as one line in the form compilers
/// use, `FILE:LINE:COLUMN: error: message`, so that editors can jump to it.
public struct SceneError: Error, Equatable, CustomStringConvertible, Sendable {
  public var file: String
  /// 1-based line; 0 when the problem is with the file as a whole.
  public var line: Int
  /// 1-based column in bytes (the format is ASCII).
  public var column: Int
  public var message: String

  public init(file: String, line: Int, column: Int, message: String) {
    self.file = file
    self.line = line
    self.column = column
    self.message = message
  }

  /// `FILE:LINE:COLUMN: error: …`; without a column (a property list's
  /// decoder names only lines) `FILE:LINE: error: …`; about the file as a
  /// whole, or a property list's key path, `FILE: error: …`.
  public var description: String {
    if line > 0 && column > 0 {
      return "\(SceneParser.escaped(file)):\(line):\(column): error: \(message)"
    }
    if line > 0 {
      return "\(SceneParser.escaped(file)):\(line): error: \(message)"
    }
    return "\(SceneParser.escaped(file)): error: \(message)"
  }
}
