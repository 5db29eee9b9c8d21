/// What the image style means for the engines, resolved here once: the
/// camera as the style builds its rays, where pixels fall on the screen,
/// the light falloff and how far a pixel's samples reach
/// (docs/CONVENTIONS.md; how values become 8-bit pixels is
/// `RenderSettings.quantization`, in Numerics). The engines ask these;
/// neither reads the style itself.
extension RenderSettings {
  /// Where this image's pixel centres fall on the screen, and back.
  @inlinable
  public var screen: ScreenMap {
    ScreenMap(style: style, width: width, height: height)
  }

  /// `camera` in precision `S`, as the style builds its rays. The mit
  /// style's sample solution takes the scene's `up` as the image's
  /// vertical axis without making it perpendicular to the view direction:
  /// for a camera looking up or down, its images are sheared vertically
  /// against the course style's. Measured: every MIT reference image with a
  /// tilted camera (scenes 02 and 04 to 07) matches to within 2 levels this
  /// way, and 50–98% of pixels with the perpendicular axis. Where up is
  /// already perpendicular the two agree.
  @inlinable
  public func camera<From: RayScalar, S: RayScalar>(
    _ camera: PerspectiveCamera<From>, as _: S.Type = S.self
  ) -> PerspectiveCamera<S> {
    var styled = PerspectiveCamera<S>(camera)
    if style == .mit { styled.up = styled.givenUp }
    return styled
  }

  /// Whether point lights fall off with distance (falloff·dist², the mit
  /// style's rule; the course's lights do not).
  @inlinable
  public var attenuatesLights: Bool { style == .mit }

  /// Whether the shaded image takes several rays per pixel.
  @inlinable
  public var supersamples: Bool { samples > 1 }

  /// Whether depth and normals too are the means of a pixel's samples.
  @inlinable
  package var supersamplesAll: Bool { supersamples && samplesAllOutputs }

  /// How far from a pixel's centre its rays can pass, in pixels beyond
  /// the pixel's own half: 0 for one ray through the centre, the filter's
  /// reach (and a sixteenth for rounding) when supersampled.
  @inlinable
  public var sampleMargin: Double { supersamples ? filter.reach + 1.0 / 16 : 0 }
}
