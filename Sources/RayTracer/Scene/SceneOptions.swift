/// What reading a scene depends on beyond its file: the image style's
/// reading of meshes.
public struct SceneOptions: Hashable, Sendable {
  /// How a mesh without `vn` lines gets its vertex normals.
  public var meshNormals: MeshNormals

  public init(meshNormals: MeshNormals) {
    self.meshNormals = meshNormals
  }

  /// The reading each image style's images were made with.
  public init(style: ImageStyle) {
    switch style {
    case .course: meshNormals = .areaWeighted
    case .mit: meshNormals = .unitMean
    }
  }
}

/// The vertex normals of a smoothed mesh (one without `vn` lines).
public enum MeshNormals: String, Hashable, Sendable {
  /// The course's loader: the sum of the unnormalised face cross products
  /// around the vertex, normalised, so large faces weigh more.
  case areaWeighted
  /// The original assignment's images: the mean of the unit normals of the
  /// faces around the vertex, normalised.
  case unitMean
}
