/// How this build of the library was compiled, as far as its behaviour
/// depends on it.
public enum BuildConfiguration {
  /// Whether `assert` is checked: true in debug builds, which build the
  /// library unoptimised and keep its assertions (see
  /// Package.swift), false in release builds.
  public static let checksAssertions: Bool = {
    var checked = false
    assert(
      {
        checked = true
        return true
      }())
    return checked
  }()
}
