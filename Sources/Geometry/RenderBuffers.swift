/// The raw result of a render, row 0 at the top, in the render's precision.
/// Each buffer is empty unless its output was asked for.
public struct RenderBuffers<Scalar: RayScalar>: Sendable {
  public let width: Int
  public let height: Int
  /// t along the unit ray direction; +inf where nothing was hit.
  public var depth: [Scalar]
  /// Unit normals; zero where nothing was hit.
  public var normals: [Vector3<Scalar>]
  /// Linear colour before clamping; the background where nothing was hit.
  public var color: [RGB<Scalar>]
  /// The normals and colours already as the style's 8-bit pixels (three
  /// bytes each, `ImageStyle.pixel`), for outputs the render was told are
  /// only written as 8-bit images (`RenderSettings.quantizedOutputs`);
  /// `normals` and `color` are then empty.
  package var normalBytes: [UInt8] = []
  package var colorBytes: [UInt8] = []

  public init(
    width: Int, height: Int, depth: [Scalar] = [],
    normals: [Vector3<Scalar>] = [],
    color: [RGB<Scalar>] = []
  ) {
    self.width = width
    self.height = height
    self.depth = depth
    self.normals = normals
    self.color = color
  }
}
