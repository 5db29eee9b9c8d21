import Geometry
import SceneDescription
import PlatformSupport

/// What reading a scene depends on beyond its file: the image style's
/// reading of meshes, and the precision the scene will be rendered in.
package struct SceneOptions: Sendable {
  /// How a mesh without `vn` lines gets its vertex normals.
  package var meshNormals: MeshNormals
  /// The render's precision: every number of the scene (and of its
  /// meshes), and every Transform's matrix, must be finite, and zero or
  /// normal, in it; the readers refuse the first that is not, where it is
  /// written (see `NumberRange.rangeProblem`). Double by default, which
  /// refuses only what Double cannot hold either.
  package var precision: NumberRange
  /// Kinds of object beyond the readers' own, read by name (the course's
  /// `CourseShapes.all`, handed down by the caller). Each must have a name
  /// of its own (`shapeNameProblem`).
  package var shapes: [ShapeKind] = []
  /// Threads that read a large scene or mesh file and parse a large mesh,
  /// as the render's: the scene and its meshes are the same for any
  /// count. Every core by default, as a render's.
  package var threads: Int

  package init(
    meshNormals: MeshNormals, precision: NumberRange = .double,
    shapes: [ShapeKind] = [], threads: Int = Platform.availableCores
  ) {
    self.meshNormals = meshNormals
    self.precision = precision
    self.shapes = shapes
    self.threads = threads
  }

  /// The reading each image style's images were made with.
  package init(
    style: ImageStyle, precision: NumberRange = .double,
    shapes: [ShapeKind] = [], threads: Int = Platform.availableCores
  ) {
    switch style {
    case .course: meshNormals = .areaWeighted
    case .mit: meshNormals = .unitMean
    }
    self.precision = precision
    self.shapes = shapes
    self.threads = threads
  }
}

extension SceneOptions {
  /// Why `shapes` cannot be read beside the readers' own kinds, or nil: a
  /// shape of one's own named like a kind of either format (it would take
  /// that kind's place without a word) or like another shape of one's own.
  func shapeNameProblem() -> String? {
    var seen: Set<String> = []
    for kind in shapes {
      if PlistSceneBuilder.objectTypes.contains(kind.name) {
        return "the shape of one's own '\(kind.name)' is named like the "
          + "scene formats' own \(kind.name): give it a name of its own"
      }
      if !seen.insert(kind.name).inserted {
        return "two shapes of one's own are named '\(kind.name)': give each "
          + "a name of its own"
      }
    }
    return nil
  }
}

/// The vertex normals of a smoothed mesh (one without `vn` lines).
package enum MeshNormals: String, Hashable, Sendable {
  /// The course's loader: the sum of the unnormalised face cross products
  /// around the vertex, normalised, so large faces weigh more.
  case areaWeighted
  /// The original assignment's images: the mean of the unit normals of the
  /// faces around the vertex, normalised.
  case unitMean
}
