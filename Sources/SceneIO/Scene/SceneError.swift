import Geometry
import SceneDescription
import Numerics

/// A problem with a scene file, reported as one line in the form compilers
/// use, `FILE:LINE:COLUMN: error: message`, so that editors can jump to it.
package struct SceneError: Error, Equatable, CustomStringConvertible, Sendable {
  package var file: String
  /// 1-based line; 0 when the problem is with the file as a whole.
  package var line: Int
  /// 1-based column in bytes (the format is ASCII).
  package var column: Int
  package var message: String
  /// What would hold the scene, when the problem is a precision's range
  /// or an engine's; the executable words it after the message.
  package var remedy: Remedy?

  package init(
    file: String, line: Int, column: Int, message: String,
    remedy: Remedy? = nil
  ) {
    self.file = file
    self.line = line
    self.column = column
    self.message = message
    self.remedy = remedy
  }

  /// The error with `remedy`.
  package func with(_ remedy: Remedy?) -> SceneError {
    var error = self
    error.remedy = remedy
    return error
  }

  /// `FILE:LINE:COLUMN: error: …`; without a column (a property list's
  /// decoder names only lines) `FILE:LINE: error: …`; about the file as a
  /// whole, or a property list's key path, `FILE: error: …`.
  package var description: String {
    if line > 0 && column > 0 {
      return "\(SceneParser.escaped(file)):\(line):\(column): error: \(message)"
    }
    if line > 0 {
      return "\(SceneParser.escaped(file)):\(line): error: \(message)"
    }
    return "\(SceneParser.escaped(file)): error: \(message)"
  }
}
