/// Where a supersampled pixel's rays go: `settings.samples` jittered,
/// stratified screen points through the pixel filter's support, the same
/// for both engines. An iterator over the samples' unit directions,
/// stratum by stratum, row-major:
///
///     var samples = PixelSamples(column: c, row: r, camera: camera,
///                                settings: settings)
///     while let direction = samples.next() { … }
///
/// The jitter comes from a generator seeded by the pixel's index, so the
/// image is the same for any thread count and either engine.
public struct PixelSamples<R: RayScalar>: IteratorProtocol {
  @usableFromInline let camera: PerspectiveCamera<R>
  @usableFromInline let filter: PixelFilter
  @usableFromInline let aspect: R
  @usableFromInline let centre: (x: R, y: R)
  /// One pixel in screen units: the distance between adjacent samples of
  /// the image's grid (`RenderSettings.screen`).
  @usableFromInline let step: (x: R, y: R)
  /// √samples strata on each axis.
  @usableFromInline let strata: Int
  @usableFromInline var generator: SplitMix64
  @usableFromInline var stratum = 0

  @inlinable @inline(__always)
  public init(
    column: Int, row: Int, camera: PerspectiveCamera<R>,
    settings: RenderSettings
  ) {
    let (width, height) = (settings.width, settings.height)
    let screen = settings.screen
    self.camera = camera
    filter = settings.filter
    aspect = R(height) / R(width)
    centre = (screen.x(column: column), screen.y(row: row))
    step = (
      width > 1 ? screen.x(column: 1) - screen.x(column: 0) as R : 2,
      height > 1 ? screen.y(row: 0) - screen.y(row: 1) as R : 2
    )
    strata = Int(Double(settings.samples).squareRoot())
    generator = SplitMix64(
      seed: UInt64(row * width + column) &* 0x9E37_79B9_7F4A_7C15)
  }

  /// The number of samples: the largest square ≤ `settings.samples`.
  @inlinable public var count: Int { strata * strata }

  @inlinable @inline(__always)
  public mutating func next() -> Vector3<R>? {
    nextThroughScreen()?.normalizedByReciprocal()
  }

  /// The next sample's direction before it is normalised: `next()` is it
  /// normalised by reciprocal (`PerspectiveCamera.throughScreen`).
  @inlinable @inline(__always)
  public mutating func nextThroughScreen() -> Vector3<R>? {
    guard stratum < count else { return nil }
    let (stratumY, stratumX) = stratum.quotientAndRemainder(dividingBy: strata)
    stratum += 1
    let u =
      (Double(stratumX) + Double.random(in: 0..<1, using: &generator))
      / Double(strata)
    let v =
      (Double(stratumY) + Double.random(in: 0..<1, using: &generator))
      / Double(strata)
    let x = centre.x + R(filter.offset(u)) * step.x
    let y = centre.y - R(filter.offset(v)) * step.y
    return camera.throughScreen(
      x: x, rowBase: camera.rowBase(y: y, aspect: aspect))
  }
}
