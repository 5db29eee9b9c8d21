/// The binary precision a scene's numbers must fit: the range the
/// readers are handed (`SceneOptions.precision`) and check every number
/// against where it is written.
package enum NumberRange: String, CaseIterable, Sendable {
  case float
  case double
}

/// Whether the numbers of a scene can be held in the precision it is
/// rendered in.
///
/// Scene readers parse numbers as Double, but a render rounds them to its
/// precision: a radius of 1e150 becomes Float's infinity and every hit is
/// lost; 1e-50 becomes 0, 1e-40 a subnormal whose square is 0. Rather than
/// draw such a scene silently empty or silently full, the readers refuse
/// it where the number is written. They learn the precision from
/// `SceneOptions.precision` (handed down by their caller) rather than
/// recording every number's position for a later check: the position is
/// at hand while a number is read, and a scene read for one precision is
/// not reused for another.
extension NumberRange {
  /// The largest finite magnitude of the precision.
  @usableFromInline
  package var largestFinite: Double {
    switch self {
    case .float: Double(Float.greatestFiniteMagnitude)
    case .double: Double.greatestFiniteMagnitude
    }
  }

  /// The smallest positive normal magnitude of the precision.
  @usableFromInline
  package var smallestNormal: Double {
    switch self {
    case .float: Double(Float.leastNormalMagnitude)
    case .double: Double.leastNormalMagnitude
    }
  }

  /// Whether `value` (finite, from a scene) rounds to a finite number in
  /// this precision that is zero only when `value` is, and never
  /// subnormal. Cheap: the fast path of every number read.
  @inlinable
  package func holds(_ value: Double) -> Bool {
    switch self {
    case .double:
      return value.isFinite && (value == 0 || value.isNormal)
    case .float:
      let rounded = Float(value)
      return rounded.isFinite && (value == 0 || rounded.isNormal)
    }
  }

  /// Why `value`, written `text` in the scene, cannot be held in this
  /// precision, or nil when it can (see `holds`). `value` is what Double
  /// reading made of `text`: infinite beyond Double's range, 0 below it,
  /// so `text` tells a written zero from one that underflowed.
  ///
  /// The message names the text, the precision and its limit; the
  /// error carries the range it exceeded (`SceneError.exceeded`).
  @usableFromInline
  package func rangeProblem(_ value: Double, text: String) -> String? {
    let overflows =
      value.isInfinite || self == .float && Float(value).isInfinite
    let roundsToZero =
      value == 0
      ? Self.writesNonZero(text) : self == .float && Float(value) == 0
    let problem: String
    if overflows {
      problem =
        "'\(text)' is beyond the finite range of \(rawValue) "
        + "(±\(limitText(largestFinite)))"
    } else if roundsToZero {
      problem =
        "'\(text)' rounds to zero in \(rawValue) (its smallest normal "
        + "number is \(limitText(smallestNormal)))"
    } else if !holds(value) {
      problem =
        "'\(text)' rounds to a subnormal number in \(rawValue) (its "
        + "smallest normal number is \(limitText(smallestNormal)))"
    } else {
      return nil
    }
    return problem
  }

  /// Whether `value` rounds to a finite number in this precision.
  @inlinable
  package func isFinite(_ value: Double) -> Bool {
    self == .float ? Float(value).isFinite : value.isFinite
  }

  /// The message for a derived quantity (a Transform's matrix, a point it
  /// moves) that leaves the precision's finite range.
  @usableFromInline
  package func overflowSuffix() -> String {
    self == .float
      ? "beyond the finite range of float"
      : "beyond the finite range of double"
  }

  func limitText(_ limit: Double) -> String {
    switch self {
    case .float: "\(Float(limit))"
    case .double: "\(limit)"
    }
  }

  /// Whether a decimal number's text has a non-zero digit before its
  /// exponent: "1e-400" is not zero even though Double reads it as 0.
  /// Words that are not decimal numbers ("inf", "nan") are not.
  static func writesNonZero(_ text: String) -> Bool {
    writesNonZero(bytes: text.utf8)
  }

  @usableFromInline
  package static func writesNonZero<Bytes: Sequence<UInt8>>(bytes: Bytes)
    -> Bool
  {
    for byte in bytes {
      switch byte {
      case UInt8(ascii: "1")...UInt8(ascii: "9"): return true
      case UInt8(ascii: "0"), UInt8(ascii: "+"), UInt8(ascii: "-"),
        UInt8(ascii: "."):
        continue
      default: return false
      }
    }
    return false
  }

  /// Whether `text` is a decimal number (digits, a sign, a point, an
  /// exponent) rather than a word such as "inf" or "nan".
  @usableFromInline
  package static func isDecimal(_ text: String) -> Bool {
    text.utf8.allSatisfy {
      ($0 >= UInt8(ascii: "0") && $0 <= UInt8(ascii: "9"))
        || $0 == UInt8(ascii: "+") || $0 == UInt8(ascii: "-")
        || $0 == UInt8(ascii: ".") || $0 == UInt8(ascii: "e")
        || $0 == UInt8(ascii: "E")
    }
  }
}
