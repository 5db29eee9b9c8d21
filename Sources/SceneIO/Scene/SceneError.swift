/// A problem with a scene file, reported as one line in the form compilers
/// use, `FILE:LINE:COLUMN: error: message`, so that editors can jump to it.
package struct SceneError: Error, Equatable, CustomStringConvertible, Sendable {
  package var file: String
  /// 1-based line; 0 when the problem is with the file as a whole.
  package var line: Int
  /// 1-based column in bytes (the format is ASCII).
  package var column: Int
  package var message: String
  /// The range a number or a moved point of the scene does not fit, when
  /// that is the problem; the executable words what would hold it.
  package var exceeded: NumberRange?

  package init(
    file: String, line: Int, column: Int, message: String,
    exceeded: NumberRange? = nil
  ) {
    self.file = file
    self.line = line
    self.column = column
    self.message = message
    self.exceeded = exceeded
  }

  /// The error, marked as one of a number beyond `range`.
  package func exceeding(_ range: NumberRange) -> SceneError {
    var error = self
    error.exceeded = range
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
