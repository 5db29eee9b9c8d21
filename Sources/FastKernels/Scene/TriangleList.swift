import Geometry
import SceneDescription
import PlatformSupport

/// The triangles of a flattened scene in file order (`Primitives`), loose
/// triangles and meshes alike: a run of meshes, each a mesh file's own
/// storage, shared rather than copied, or the loose triangles between two
/// mesh files gathered into a mesh of their own.
///
/// As a collection it yields the triangles one by one, each made on demand
/// (`TriangleMesh.triangle(at:)`), in the order the scene gives them; its
/// equality is that of the triangles in order, whatever parts hold them.
@usableFromInline
package struct TriangleList<Scalar: RayScalar>: Sendable {
  /// The meshes, in order.
  package private(set) var parts: [TriangleMesh<Scalar>] = []
  /// Per part, the count of triangles up to its end.
  private var ends: [Int] = []
  /// Whether the last part gathers loose triangles, and may grow; a mesh
  /// appended whole is shared with the scene and never grown.
  private var lastPartIsLoose = false

  @usableFromInline
  package init() {}

  /// The triangles in order, gathered into one mesh.
  @usableFromInline
  package init(_ triangles: some Sequence<Triangle<Scalar>>) {
    for triangle in triangles { append(triangle) }
  }

  /// Appends a loose triangle.
  @usableFromInline
  package mutating func append(_ triangle: Triangle<Scalar>) {
    if !lastPartIsLoose {
      parts.append(TriangleMesh())
      ends.append(ends.last ?? 0)
      lastPartIsLoose = true
    }
    parts[parts.count - 1].append(triangle)
    ends[ends.count - 1] += 1
  }

  /// Appends a mesh's triangles, sharing its storage.
  @usableFromInline
  package mutating func append(_ mesh: TriangleMesh<Scalar>) {
    guard !mesh.isEmpty else { return }
    parts.append(mesh)
    ends.append((ends.last ?? 0) + mesh.count)
    lastPartIsLoose = false
  }

  /// The list with `transform` applied to each part; it must keep each
  /// part's triangle count (scaling, say).
  func mapParts(
    _ transform: (TriangleMesh<Scalar>) -> TriangleMesh<Scalar>
  ) -> TriangleList {
    var result = self
    result.parts = parts.map(transform)
    return result
  }
}

extension TriangleList: RandomAccessCollection {
  @usableFromInline
  package var startIndex: Int { 0 }
  @usableFromInline
  package var endIndex: Int { ends.last ?? 0 }

  /// - Complexity: O(log of the number of parts).
  @usableFromInline
  package subscript(position: Int) -> Triangle<Scalar> {
    // The first part ending after `position`.
    var (low, high) = (0, ends.count - 1)
    while low < high {
      let middle = (low + high) / 2
      if ends[middle] > position { high = middle } else { low = middle + 1 }
    }
    let start = low == 0 ? 0 : ends[low - 1]
    return parts[low].triangle(at: position - start)
  }

  @usableFromInline
  package struct Iterator: IteratorProtocol {
    let parts: [TriangleMesh<Scalar>]
    var part = 0
    var index = 0

    @usableFromInline
    package mutating func next() -> Triangle<Scalar>? {
      while part < parts.count {
        if index < parts[part].count {
          defer { index += 1 }
          return parts[part].triangle(at: index)
        }
        part += 1
        index = 0
      }
      return nil
    }
  }

  /// Part by part, without a search per triangle.
  @usableFromInline
  package func makeIterator() -> Iterator { Iterator(parts: parts) }
}

extension TriangleList: Equatable {
  /// The same triangles in the same order.
  @usableFromInline
  package static func == (lhs: TriangleList, rhs: TriangleList) -> Bool {
    lhs.count == rhs.count && lhs.elementsEqual(rhs)
  }
}

extension TriangleList: ExpressibleByArrayLiteral {
  @usableFromInline
  package init(arrayLiteral triangles: Triangle<Scalar>...) {
    self.init(triangles)
  }
}
