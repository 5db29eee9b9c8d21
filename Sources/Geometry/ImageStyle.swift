/// Which of the two conventions measured from the course's images (see
/// docs/CONVENTIONS.md): where pixels sample the screen, and how depth,
/// normals and colour become 8-bit values.
public enum ImageStyle: String, CaseIterable, Sendable {
  /// The Swift course: its own pixel mapping (columns at pixel centres,
  /// rows one pixel above them), depth range from the image, |n|,
  /// truncation.
  case course
  /// The original assignment: pixel corners, depth range from the command
  /// line, (n + 1)/2, rounding, point lights attenuated by falloff·dist².
  case mit
}
