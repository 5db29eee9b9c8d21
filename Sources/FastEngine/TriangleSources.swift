import Geometry
import SceneDescription
import PlatformSupport

/// Where each compiled triangle's material and vertex normals are read at
/// a hit: the face of the scene's mesh it was compiled from, through that
/// mesh's own index arrays, which the scene holds anyway.
///
/// A material and three normal indices per triangle, 16 bytes, had been
/// 76 MiB of a 5·10⁶-triangle render's 796 MiB peak (docs/PERFORMANCE.md,
/// "Large meshes"); they are read once per pixel, not per
/// test. Here a triangle costs 4 bytes, its face's number, and nothing
/// while every compiled triangle is the face of the same number (no
/// degenerate face left out, no large one moved after the others, no
/// hierarchy's order): a mesh rendered through screen tiles.
struct TriangleSources: Sendable {
  /// Per mesh, in the list's order, what its faces' materials and normals
  /// are read from: the mesh's own arrays, shared with the scene, not
  /// copied (a transformed mesh's placed vertices are not kept alive).
  private var meshes: [Faces] = []
  /// Per mesh, the face number of its first triangle.
  private var firsts: [Int] = []
  /// The faces' count so far: the next mesh's first face number.
  private var faces = 0
  /// Per compiled triangle, its face number; empty while `followsFaces`.
  private var numbers: [Int32] = []
  /// Compiled triangles so far.
  private(set) var count = 0
  /// How many the compile expects at most: the room face numbers, once
  /// stored, are given at once.
  private var expected = 0

  /// Whether compiled triangle k is face k for every k: no face numbers
  /// are stored.
  private(set) var followsFaces = true

  /// Adds `mesh`, whose faces follow the earlier meshes' in numbering,
  /// its normals at `normalBase` in the compiled normals.
  mutating func add(_ mesh: TriangleMesh<Double>, normalBase: Int) {
    meshes.append(
      Faces(
        material: mesh.materialIndex, materials: mesh.materialIndices,
        normals: mesh.normalsFollowVertices
          ? mesh.vertexIndices : mesh.normalIndices, normalBase: normalBase))
    firsts.append(faces)
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

  /// Appends compiled triangles made from the faces `faces` in order but
  /// those of `leftOut` (increasing, within `faces`): a part of a mesh
  /// compiled on a thread of its own.
  mutating func append(faces: Range<Int>, leavingOut leftOut: [Int]) {
    if followsFaces && leftOut.isEmpty && faces.lowerBound == count {
      count += faces.count
      return
    }
    var next = 0
    for face in faces {
      if next < leftOut.count && leftOut[next] == face {
        next += 1
      } else {
        append(face: face)
      }
    }
  }

  /// Expects at most `total` compiled triangles in all.
  mutating func expect(_ total: Int) { expected = total }

  /// Stores the face numbers so far, k for triangle k, with room for the
  /// triangles expected.
  private mutating func storeNumbers() {
    numbers.reserveCapacity(Swift.max(expected, count))
    numbers += (0..<count).lazy.map { Int32(truncatingIfNeeded: $0) }
    followsFaces = false
  }

  /// Puts the triangles into the hierarchy's leaf order (`arrange`).
  mutating func arrange(_ hierarchy: BoundingVolumeHierarchy<some RayScalar>) {
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
  @inline(__always)
  func material(_ index: Int) -> Int32 {
    let (mesh, face) = locate(index)
    let materials = meshes[mesh].materials
    return Int32(
      truncatingIfNeeded: materials.isEmpty
        ? meshes[mesh].material : materials[face])
  }

  /// Compiled triangle `index`'s normals in the compiled normals, or −1s.
  @inline(__always)
  func normals(_ index: Int) -> TriangleNormalIndices {
    let (mesh, face) = locate(index)
    let normals = meshes[mesh].normals
    guard !normals.isEmpty, normals[3 * face] >= 0 else { return .none }
    let base = Int32(truncatingIfNeeded: meshes[mesh].normalBase)
    return TriangleNormalIndices(
      n0: base + normals[3 * face], n1: base + normals[3 * face + 1],
      n2: base + normals[3 * face + 2])
  }

  /// A mesh's arrays that its faces' materials and normals are read from
  /// (`TriangleMesh`'s, shared).
  private struct Faces: Sendable {
    /// Every face's material, unless `materials` gives one each.
    var material: Int
    var materials: [Int]
    /// Three per face into the mesh's normals, −1s for a face without;
    /// empty when none has them. A mesh whose normals follow its vertices
    /// gives its vertex indices.
    var normals: [Int32]
    /// Where the mesh's normals begin in `CompiledScene.vertexNormals`.
    var normalBase: Int
  }
}
