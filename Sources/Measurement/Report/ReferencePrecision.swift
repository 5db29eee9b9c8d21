import SceneIO
import Geometry
import SceneDescription

/// The precision the accuracy reference intersects in, as chosen on the
/// command line (`raytrace report --reference`).
package enum ReferencePrecision: String, CaseIterable, Sendable {
  /// Float80 (64-bit significand, IEEE): x86 only.
  case float80
  /// DoubleDouble (106-bit significand, see its bounds): every platform.
  case doubleDouble = "double-double"

  /// ReferenceScalar's: Float80 where the platform has it.
  package static var platformDefault: ReferencePrecision {
    #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
      .float80
    #else
      .doubleDouble
    #endif
  }

  /// Whether this platform has the type.
  package var isAvailable: Bool {
    self == .doubleDouble || Self.platformDefault == .float80
  }
}
