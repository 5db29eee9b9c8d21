/// What a user can do about a scene that a precision or an engine cannot
/// hold. Messages below the executable say what is wrong; the executable,
/// which knows its own options, words the remedy.
@usableFromInline
package enum Remedy: Sendable, Hashable {
  /// The scene fits in Double where it does not in Float.
  case doublePrecision
  /// The fast engine, which scales its lengths, draws what the course
  /// engine's own lengths cannot.
  case fastEngine
}

extension Precision {
  /// The remedy for a number or a transform this precision cannot hold:
  /// Double for Float, none for Double.
  @usableFromInline
  package var remedy: Remedy? { self == .float ? .doublePrecision : nil }
}
