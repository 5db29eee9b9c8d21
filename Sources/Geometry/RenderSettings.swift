/// The images a render is asked for. Anything not asked for is not computed:
/// no shading without `shaded`, no normals unless `normals` or `shaded`, no
/// depth buffer without `depth`.
public struct RenderOutputs: OptionSet, Hashable, Sendable {
  public let rawValue: Int
  public init(rawValue: Int) { self.rawValue = rawValue }

  public static let depth = RenderOutputs(rawValue: 1)
  public static let normals = RenderOutputs(rawValue: 2)
  public static let shaded = RenderOutputs(rawValue: 4)

  /// Normals are computed for the normals image and for shading.
  public var needsNormals: Bool { !isDisjoint(with: [.normals, .shaded]) }

  public var names: [String] {
    [
      (RenderOutputs.depth, "depth"), (.normals, "normals"),
      (.shaded, "shaded"),
    ]
    .filter { contains($0.0) }.map(\.1)
  }
}

/// Everything about a render but the scene.
public struct RenderSettings: Sendable {
  public var width: Int
  public var height: Int
  public var outputs: RenderOutputs
  public var style: ImageStyle
  /// Worker threads; the image is the same, bit for bit, for any count.
  public var threads: Int
  /// Camera rays per pixel for the shaded image, a perfect square: jittered
  /// on a √N × √N grid of strata. Depth and normals take the pixel's centre,
  /// unless `samplesAllOutputs`.
  public var samples: Int = 1
  /// Depth and normals averaged over the shaded image's samples: the depth
  /// of the samples that hit (∞ when none does), the normals' mean with a
  /// miss counted as zero (docs/CONVENTIONS.md, "Supersampling").
  public var samplesAllOutputs = false
  /// How samples are spread over and weighted around a pixel.
  public var filter: PixelFilter = .box
  /// Outputs (normals, shaded) that are only written as 8-bit images: the
  /// render stores them straight as the style's pixels
  /// (`RenderBuffers.normalBytes`, `colorBytes`), three bytes a pixel
  /// instead of three numbers of the render's precision.
  public var quantizedOutputs: RenderOutputs = []

  public init(
    width: Int, height: Int, outputs: RenderOutputs,
    style: ImageStyle = .course, threads: Int = 1
  ) {
    self.width = width
    self.height = height
    self.outputs = outputs
    self.style = style
    self.threads = threads
  }
}

/// The reconstruction filter of supersampled shading.
public enum PixelFilter: String, CaseIterable, Sendable {
  /// Samples uniform over the pixel's square, equally weighted.
  case box
  /// Samples over the 2×2-pixel support of the tent (1 − |x|)(1 − |y|),
  /// drawn from it by inverting its distribution, so equally weighted too.
  case tent

  /// How far from the pixel's centre, in pixels along each axis, a
  /// sample can lie: the largest |`offset(u)`|.
  public var reach: Double {
    switch self {
    case .box: 0.5
    case .tent: 1
    }
  }

  /// The offset from the pixel's centre, in pixels, of stratum position
  /// u ∈ [0, 1).
  @inlinable
  public func offset(_ u: Double) -> Double {
    switch self {
    case .box: return u - 0.5
    case .tent:
      return u < 0.5 ? (2 * u).squareRoot() - 1 : 1 - (2 - 2 * u).squareRoot()
    }
  }
}
