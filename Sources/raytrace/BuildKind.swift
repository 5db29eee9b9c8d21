/// How this executable was built.
enum BuildKind {
  /// Whether it was built optimised (`swift build -c release`, or Xcode's
  /// Release): SwiftPM and Xcode define DEBUG in debug builds only.
  static var isOptimized: Bool {
    #if DEBUG
      false
    #else
      true
    #endif
  }
}
