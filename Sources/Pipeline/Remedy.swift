import FastEngine
import FastKernels
import SceneIO

/// What a user can do about a scene that a precision or an engine cannot
/// hold. Messages below the executable say what is wrong; the executable,
/// which knows its own options, words the remedy.
package enum Remedy: Sendable, Hashable {
  /// The scene fits in Double where it does not in Float.
  case doublePrecision
  /// The fast engine, which scales its lengths, draws what the course
  /// engine's own lengths cannot.
  case fastEngine

  /// The remedy for a number or a transform the range `exceeded` cannot
  /// hold: Double for Float, none for Double (or for no range).
  package init?(exceeded: NumberRange?) {
    guard exceeded == .float else { return nil }
    self = .doublePrecision
  }
}

extension Precision {
  /// The remedy for a number or a transform this precision cannot hold:
  /// Double for Float, none for Double.
  package var remedy: Remedy? { Remedy(exceeded: numberRange) }

  /// The range the readers check the scene's numbers against for a render
  /// in this precision.
  package var numberRange: NumberRange {
    switch self {
    case .float: .float
    case .double: .double
    }
  }
}
