import Geometry
import SceneDescription
import Numerics
import PlatformSupport

/// Where each compiled triangle's material and vertex normals are read at
/// a hit: the face of the scene's mesh it was compiled from, through that
/// mesh's own index arrays, which the scene holds anyway.
///
/// A material and three normal indices per triangle, 16 bytes, had been
/// 76 MiB of a 5·10⁶-triangle render's 796 MiB peak (docs/PERFORMANCE.md,
/// "Memory and parallel reading"); they are read once per pixel, not per
/// test. Here a triangle costs 4 bytes, its face's number, and nothing
/// while every compiled triangle is the face of the same number (no
/// degenerate face left out, no large one moved after the others, no
/// hierarchy's order): a mesh rendered through screen tiles.
struct TriangleSources: Sendable {
  /// The meshes in the list's order without their vertices and normals,
  /// which the records and `CompiledScene.vertexNormals` hold: only index
  /// arrays and materials, shared with the scene (a transformed mesh's
  /// placed vertices are not kept alive by them).
  private var meshes: [TriangleMesh<Double>] = []
  /// Per mesh, the face number of its first triangle.
  private var firsts: [Int] = []
  /// Per mesh, where its normals begin in `CompiledScene.vertexNormals`.
  private var normalBases: [Int] = []
  /// The faces' count so far: the next mesh's first face number.
  private var faces = 0
  /// Per compiled triangle, its face number; empty while `followsFaces`.
  private var numbers: [Int32] = []
  /// Compiled triangles so far.
  private(set) var count = 0

  /// Whether compiled triangle k is face k for every k: no face numbers
  /// are stored.
  private(set) var followsFaces = true

  /// Adds `mesh`, whose faces follow the earlier meshes' in numbering,
  /// its normals at `normalBase` in the compiled normals.
  mutating func add(_ mesh: TriangleMesh<Double>, normalBase: Int) {
    var indexed = mesh
    indexed.vertices = []
    indexed.normals = []
    meshes.append(indexed)
    firsts.append(faces)
    normalBases.append(normalBase)
    faces += mesh.count
  }

  /// The face number of face `index` of the mesh added last.
  func face(_ index: Int) -> Int { firsts[firsts.count - 1] + index }

  /// Appends a compiled triangle made from face `face`.
  mutating func append(face: Int) {
    if followsFaces && face != count { storeNumbers() }
    if !followsFaces { numbers.append(Int32(truncatingIfNeeded: face)) }
    count += 1
  }

  /// Stores the face numbers so far, k for triangle k.
  private mutating func storeNumbers() {
    numbers = (0..<count).map { Int32(truncatingIfNeeded: $0) }
    followsFaces = false
  }

  /// Puts the triangles into the hierarchy's leaf order (`arrange`).
  mutating func arrange(_ hierarchy: BoundingVolumeHierarchy<some RayScalar>)
  {
    if followsFaces { storeNumbers() }
    hierarchy.arrange(&numbers)
  }

  /// Compiled triangle `index`'s mesh and its face's index in that mesh.
  @inline(__always)
  private func locate(_ index: Int) -> (mesh: Int, face: Int) {
    let face = followsFaces ? index : Int(numbers[index])
    // The last mesh starting at or before the face: one compare for a
    // scene of one mesh.
    var (low, high) = (0, firsts.count - 1)
    while low < high {
      let middle = (low + high + 1) / 2
      if firsts[middle] <= face { low = middle } else { high = middle - 1 }
    }
    return (low, face - firsts[low])
  }

  /// Compiled triangle `index`'s material.
  func material(_ index: Int) -> Int32 {
    let (mesh, face) = locate(index)
    return Int32(truncatingIfNeeded: meshes[mesh].material(at: face))
  }

  /// Compiled triangle `index`'s normals in the compiled normals, or −1s.
  func normals(_ index: Int) -> TriangleNormalIndices {
    let (mesh, face) = locate(index)
    guard let corners = meshes[mesh].normalCorners(face) else { return .none }
    let base = normalBases[mesh]
    return TriangleNormalIndices(
      n0: Int32(truncatingIfNeeded: base + corners.0),
      n1: Int32(truncatingIfNeeded: base + corners.1),
      n2: Int32(truncatingIfNeeded: base + corners.2))
  }
}
