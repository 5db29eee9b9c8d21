import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

/// A mesh file's triangles as one scene entry (`TriangleMesh`): hit,
/// placed, flattened and scaled exactly as the group of the same triangles.
final class TriangleMeshModelTests: XCTestCase {
  /// A fan of `count` triangles around the z axis at z = −5, with vertex
  /// normals, and twins of the first two (coincident: ties).
  func fan(_ count: Int) -> [Triangle<Double>] {
    var triangles: [Triangle<Double>] = []
    for index in 0..<count {
      let a = 2 * Double.pi * Double(index) / Double(count)
      let b = 2 * Double.pi * Double(index + 1) / Double(count)
      let normals = Triangle<Double>.VertexNormals(
        Vector3(0, 0, 1), Vector3(cos(a), sin(a), 1).normalized(),
        Vector3(cos(b), sin(b), 1).normalized())
      triangles.append(
        Triangle(
          Vector3(0, 0, -5), Vector3(2 * cos(a), 2 * sin(a), -5.5),
          Vector3(2 * cos(b), 2 * sin(b), -5.5), vertexNormals: normals,
          materialIndex: index % 3))
    }
    return triangles
      + triangles.prefix(2).map {
        var twin = $0
        twin.materialIndex = 7
        return twin
      }
  }

  func rays() -> [Ray<Double>] {
    var generator = SplitMix64(seed: 0x6d65_7368)
    return (0..<500).map { _ in
      Ray(
        origin: Vector3(0.1, -0.2, 1),
        direction: Vector3(
          generator.uniform(-0.5...0.5), generator.uniform(-0.5...0.5), -1))
    }
  }

  /// The same hits, t, normal and material, as the group of the same
  /// triangles, ties to the earlier triangle included.
  func testIntersect_AsTheGroup() {
    let triangles = fan(12)
    let mesh = SceneObject.mesh(TriangleMesh(triangles))
    let group = SceneObject.group(Group(triangles.map { .triangle($0) }))
    var hits = 0
    for ray in rays() {
      for method in IntersectionMethod.allCases {
        let want = group.intersect(
          ray, after: 0, before: .infinity, method: method)
        let got = mesh.intersect(
          ray, after: 0, before: .infinity, method: method)
        XCTAssertEqual(got?.t, want?.t)
        XCTAssertEqual(got?.normal, want?.normal)
        XCTAssertEqual(got?.materialIndex, want?.materialIndex)
        if want != nil { hits += 1 }
      }
    }
    XCTAssertGreaterThan(hits, 100)
  }

  /// Flattened, transformed or not, beside other triangles or alone, the
  /// mesh gives the triangles the group of them gives, in the same order.
  func testFlattened_AsTheGroup() {
    let triangles = fan(8)
    let loose = Triangle<Double>(
      Vector3(1, 1, -3), Vector3(2, 1, -3), Vector3(1, 2, -3))
    let matrix =
      Matrix4<Double>.translation(Vector3(1, 2, 3))
      * Matrix4.rotationY(degrees: 30) * Matrix4.scale(Vector3(1, 2, 0.5))
    func scenes(_ meshObject: SceneObject<Double>) -> [Group<Double>] {
      [
        Group([meshObject]),
        Group([.triangle(loose), meshObject, .triangle(loose)]),
        Group([
          .transform(Transform(matrix: matrix, object: meshObject)!),
          meshObject,
        ]),
      ]
    }
    let asMesh = scenes(.mesh(TriangleMesh(triangles)))
    let asGroup = scenes(.group(Group(triangles.map { .triangle($0) })))
    for (mesh, group) in zip(asMesh, asGroup) {
      XCTAssertEqual(mesh.flattened().triangles, group.flattened().triangles)
      XCTAssertEqual(
        LengthScale.largestLength(mesh.flattened(), eye: .zero),
        LengthScale.largestLength(group.flattened(), eye: .zero))
    }
    // Scaled by a power of two, triangle by triangle.
    XCTAssertEqual(
      asMesh[2].flattened().scaled(by: 0x1p-70).triangles,
      asGroup[2].flattened().scaled(by: 0x1p-70).triangles)
  }

  /// The scale checks see a mesh's triangles as the group's: a triangle
  /// 10⁻²⁵ across three units from the eye, beside a sphere 10²⁰ wide, is
  /// refused in float with the same words either way.
  func testScaleProblem_AsTheGroup() throws {
    let speck = Triangle<Double>(
      Vector3(-1e-25, -1e-25, -3), Vector3(1e-25, -1e-25, -3),
      Vector3(0, 1e-25, -3))
    let far = SceneObject<Double>.sphere(
      Sphere(center: Vector3(0, 0, -3e21), radius: 1e20))
    let camera = try XCTUnwrap(
      PerspectiveCamera<Double>(
        center: .zero, direction: Vector3(0, 0, -1), up: Vector3(0, 1, 0),
        angle: 30))
    func problem(_ triangles: SceneObject<Double>) -> String? {
      LengthScale.problem(
        Scene(camera: camera, root: Group([far, triangles])),
        precision: .float)
    }
    let asGroup = problem(.group(Group([.triangle(speck)])))
    XCTAssertNotNil(asGroup)
    XCTAssertEqual(problem(.mesh(TriangleMesh([speck]))), asGroup)
  }

  /// An untransformed mesh is not copied when flattened: the primitives
  /// hold its own storage, alone or beside loose triangles, which come
  /// before and after it in file order.
  func testFlattened_SharesTheMesh() {
    let triangles = fan(8)
    let mesh = TriangleMesh(triangles)
    func storage(_ mesh: TriangleMesh<Double>) -> UnsafePointer<Int32>? {
      mesh.vertexIndices.withUnsafeBufferPointer { $0.baseAddress }
    }
    let alone = Group([.mesh(mesh)]).flattened().triangles
    XCTAssertEqual(alone.parts.map(storage), [storage(mesh)])
    XCTAssertEqual(Array(alone), triangles)
    let beside = Group([
      .triangle(triangles[0]), .mesh(mesh), .triangle(triangles[1]),
    ]).flattened().triangles
    XCTAssertEqual(beside.parts.count, 3)
    XCTAssertEqual(storage(beside.parts[1]), storage(mesh))
    XCTAssertEqual(Array(beside), [triangles[0]] + triangles + [triangles[1]])
  }

  /// Triangles with and without vertex normals and texture coordinates, in
  /// every order of the two, each with its own material.
  func mixed() -> [Triangle<Double>] {
    let plain = fan(6)
    var triangles: [Triangle<Double>] = []
    for (index, triangle) in plain.enumerated() {
      var triangle = triangle
      if index % 3 == 1 { triangle.vertexNormals = nil }
      if index % 2 == 0 {
        triangle.textureCoordinates = Triangle.TextureCoordinates(
          TextureCoordinate(0, Double(index)), TextureCoordinate(1, 0.5),
          TextureCoordinate(0.25, 1))
      }
      triangle.materialIndex = index * 5 + 1
      triangles.append(triangle)
    }
    var flat = plain[0]
    flat.vertexNormals = nil
    return [flat] + triangles + [flat]
  }

  /// Loose triangles appended one by one come back as they went in.
  func testAppend_GivesTheTrianglesBack() {
    for triangles in [mixed(), fan(5), Array(mixed().suffix(3)), []] {
      let mesh = TriangleMesh(triangles)
      XCTAssertEqual(Array(mesh), triangles)
      XCTAssertEqual(mesh.count, triangles.count)
      for index in triangles.indices {
        XCTAssertEqual(mesh.triangle(at: index), triangles[index])
        XCTAssertEqual(mesh.material(at: index), triangles[index].materialIndex)
      }
    }
  }

  /// A smoothed mesh (normals by vertex) that gains a loose triangle keeps
  /// its triangles' normals, with or without the new one's.
  func testAppend_ToNormalsByVertex() throws {
    let obj = try OBJReader.parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nf 1 2 3\nf 2 4 3\n",
      file: "quad.obj")
    let smoothed = TriangleMesh(obj, materialIndex: 2, normals: .unitMean)
    XCTAssertTrue(smoothed.normalsFollowVertices)
    for extra in mixed().prefix(3) {
      var mesh = smoothed
      mesh.append(extra)
      XCTAssertEqual(Array(mesh), Array(smoothed) + [extra])
    }
  }

  /// Placed and scaled as a whole, the mesh gives the triangles placed and
  /// scaled one by one (`Triangle.moved`, `scaled`), bit for bit.
  func testMovedAndScaled_AsEachTriangle() throws {
    let triangles = mixed()
    let matrix =
      Matrix4<Double>.translation(Vector3(1, 2, 3))
      * Matrix4.rotationY(degrees: 30) * Matrix4.scale(Vector3(1e-40, 2, 0.5))
    let mesh = TriangleMesh(triangles)
    XCTAssertEqual(
      Array(mesh.moved(by: matrix)), triangles.map { $0.moved(by: matrix) })
    XCTAssertEqual(
      Array(mesh.scaled(by: 0x1p-70)), triangles.map { $0.scaled(by: 0x1p-70) })
    let obj = try OBJReader.parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nf 1 2 3\nf 2 4 3\n",
      file: "quad.obj")
    let smoothed = TriangleMesh(obj, materialIndex: 2, normals: .unitMean)
    XCTAssertEqual(
      Array(smoothed.moved(by: matrix)),
      smoothed.map { $0.moved(by: matrix) })
  }
}
