// libFuzzer harness for the OBJ reader (`Fuzz/run.sh obj`).
//
// Each input is an OBJ file's bytes. Whatever they hold, the reader must
// return a mesh whose every index is in range, or throw one well-formed
// `mesh.obj:LINE:COLUMN: error:` line pointing inside the input; a mesh
// must also smooth and triangulate without trapping. Anything else stops
// the fuzzer, which saves the input.

@testable import FastEngine
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport

@_cdecl("LLVMFuzzerTestOneInput")
public func fuzzOBJReader(_ data: UnsafePointer<UInt8>?, _ size: Int) -> CInt {
  let bytes =
    data.map { Array(UnsafeBufferPointer(start: $0, count: size)) } ?? []
  let mesh: OBJMesh
  do throws(SceneError) {
    mesh = try OBJReader.parse(bytes: bytes, file: "mesh.obj")
  } catch {
    let description = error.description
    guard
      description.utf8.starts(
        with: "mesh.obj:\(error.line):\(error.column): error: ".utf8),
      !description.utf8.contains(UInt8(ascii: "\n"))
    else {
      fatalError(
        "fuzz invariant: malformed error \(description.debugDescription)")
    }
    let lines = bytes.split(
      separator: UInt8(ascii: "\n"), omittingEmptySubsequences: false)
    guard (1...lines.count).contains(error.line),
      (1...(lines[error.line - 1].count + 1)).contains(error.column)
    else {
      fatalError(
        "fuzz invariant: position \(error.line):\(error.column) outside the input"
      )
    }
    return 0
  }
  for face in mesh.triangles {
    for index in [
      face.vertexIndices.x, face.vertexIndices.y, face.vertexIndices.z,
    ]
    where !(0..<Int32(mesh.vertices.count)).contains(index) {
      fatalError(
        "fuzz invariant: vertex index \(index) of \(mesh.vertices.count)")
    }
    if let normals = face.normalIndices {
      for index in [normals.x, normals.y, normals.z]
      where !(0..<Int32(mesh.normals.count)).contains(index) {
        fatalError(
          "fuzz invariant: normal index \(index) of \(mesh.normals.count)")
      }
    }
  }
  // The scene's mesh, as `MeshLoader` makes it, and each of its triangles.
  let triangles = TriangleMesh(mesh, materialIndex: 0, normals: .unitMean)
  for triangle in triangles { _ = triangle.geometricNormal }
  return 0
}
