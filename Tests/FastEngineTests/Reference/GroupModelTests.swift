import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

final class GroupModelTests: XCTestCase {
  /// Spheres on the −z axis at 10, 20, 30 (radius 1, materials 1, 2, 3)
  /// and the plane z = −15 (material 4), seen from the origin down −z.
  func objects<T: RayScalar>(_: T.Type) -> [SceneObject<T>] {
    [
      .sphere(Sphere(center: Vector3(0, 0, -20), radius: 1, materialIndex: 2)),
      .sphere(Sphere(center: Vector3(0, 0, -10), radius: 1, materialIndex: 1)),
      .plane(Plane(normal: Vector3(0, 0, 1), offset: -15, materialIndex: 4)),
      .sphere(Sphere(center: Vector3(0, 0, -30), radius: 1, materialIndex: 3)),
    ]
  }

  func checkNearestInAnyOrder<T: RayScalar>(_: T.Type) {
    let ray = Ray<T>(origin: .zero, direction: Vector3(0, 0, -1))
    let all = objects(T.self)
    // Every rotation and its reverse: the nearest must not depend on order.
    for shift in all.indices {
      let rotated = Array(all[shift...] + all[..<shift])
      for order in [rotated, rotated.reversed()] {
        let hit = Group(order).intersect(ray, after: 0, before: .infinity)
        XCTAssertEqual(hit?.t, 9, "\(T.self) \(order.map(\.kind))")
        XCTAssertEqual(hit?.materialIndex, 1)
        XCTAssertEqual(hit?.normal, Vector3(0, 0, 1))
      }
    }
  }

  func testIntersect_NearestInAnyOrder_Float() {
    checkNearestInAnyOrder(Float.self)
  }
  func testIntersect_NearestInAnyOrder_Double() {
    checkNearestInAnyOrder(Double.self)
  }

  /// The interval narrows hit by hit and is honoured throughout: with tMin
  /// past the first sphere the plane (t = 15) is nearest; with tMax at 9
  /// (open) nothing is.
  func checkInterval<T: RayScalar>(_: T.Type) {
    let group = Group(objects(T.self))
    let ray = Ray<T>(origin: .zero, direction: Vector3(0, 0, -1))
    let cases: [(T, T, t: T?, material: Int?)] = [
      (0, .infinity, 9, 1),
      (9, .infinity, 11, 1),  // the far side of the first sphere
      (11, .infinity, 15, 4),
      (15, .infinity, 19, 2),
      (0, 9, nil, nil),
      (31, .infinity, nil, nil),
      (16, 18, nil, nil),
    ]
    for (tMin, tMax, t, material) in cases {
      let hit = group.intersect(ray, after: tMin, before: tMax)
      XCTAssertEqual(hit?.t, t, "\(T.self) (\(tMin), \(tMax))")
      XCTAssertEqual(
        hit?.materialIndex, material, "\(T.self) (\(tMin), \(tMax))")
    }
  }

  func testIntersect_Interval_Float() { checkInterval(Float.self) }
  func testIntersect_Interval_Double() { checkInterval(Double.self) }

  func testIntersect_Empty() {
    let empty = Group<Double>()
    let ray = Ray<Double>(origin: .zero, direction: Vector3(0, 0, -1))
    XCTAssertNil(empty.intersect(ray, after: 0, before: .infinity))
    XCTAssertNil(
      Group([.group(empty), .group(Group())]).intersect(
        ray, after: 0, before: .infinity))
  }

  /// A nearer object inside a nested group beats a farther one outside it,
  /// and the other way round.
  func testIntersect_NestedGroups() {
    let near = SceneObject<Double>.sphere(
      Sphere(center: Vector3(0, 0, -5), radius: 1, materialIndex: 7))
    let far = SceneObject<Double>.sphere(
      Sphere(center: Vector3(0, 0, -50), radius: 1, materialIndex: 8))
    let ray = Ray<Double>(origin: .zero, direction: Vector3(0, 0, -1))
    let deep = Group([.group(Group([.group(Group([near]))]))])
    for group in [Group([far, .group(deep)]), Group([.group(deep), far])] {
      let hit = group.intersect(ray, after: 0, before: .infinity)
      XCTAssertEqual(hit?.t, 4)
      XCTAssertEqual(hit?.materialIndex, 7)
    }
    let farInside = Group([near, .group(Group([far]))])
    XCTAssertEqual(farInside.intersect(ray, after: 5, before: .infinity)?.t, 6)
    XCTAssertEqual(
      farInside.intersect(ray, after: 6, before: .infinity)?.materialIndex, 8)
  }

  /// `flattened()` flattens nested groups in file (depth-first) order.
  func testFlattened_NestedGroupsInFileOrder() {
    func sphere(_ index: Int) -> SceneObject<Double> {
      .sphere(
        Sphere(
          center: Vector3(Double(index), 0, 0), radius: 1, materialIndex: index)
      )
    }
    func plane(_ index: Int) -> SceneObject<Double> {
      .plane(
        Plane(
          normal: Vector3(0, 1, 0), offset: Double(index), materialIndex: index)
      )
    }
    let root = Group([
      sphere(0), plane(0),
      .group(
        Group([sphere(1), .group(Group([sphere(2), plane(1)])), sphere(3)])),
      plane(2), sphere(4),
    ])
    let all = root.flattened()
    let (spheres, planes) = (all.spheres, all.planes)
    XCTAssertEqual(spheres.map(\.materialIndex), [0, 1, 2, 3, 4])
    XCTAssertEqual(planes.map(\.materialIndex), [0, 1, 2])
    XCTAssertTrue(Group<Double>().flattened().spheres.isEmpty)
  }

  /// Spheres straight in the root group, spheres nested or moved by a
  /// transform and the other kinds come out in file order within each kind.
  func testFlattened_MixedKindsKeepFileOrder() throws {
    func sphere(_ index: Int) -> Sphere<Double> {
      Sphere(
        center: Vector3(Double(index), 0, 0), radius: 1, materialIndex: index)
    }
    let shift = try XCTUnwrap(
      Transform(
        matrix: .translation(Vector3(0, 5, 0)), object: .sphere(sphere(2))))
    let squash = try XCTUnwrap(
      Transform(matrix: .scale(Vector3(1, 2, 1)), object: .sphere(sphere(9))))
    let triangle = Triangle<Double>(
      Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), materialIndex: 7)
    let root = Group([
      .sphere(sphere(0)), .triangle(triangle), .sphere(sphere(1)),
      .transform(shift), .transform(squash),
      .group(Group([.sphere(sphere(3)), .triangle(triangle)])),
      .sphere(sphere(4)),
    ])
    let all = root.flattened()
    XCTAssertEqual(all.spheres.map(\.materialIndex), [0, 1, 2, 3, 4])
    XCTAssertEqual(all.spheres[2].center, Vector3(2, 5, 0))
    XCTAssertEqual(all.triangles.count, 2)
    XCTAssertEqual(all.transformedSpheres.map(\.sphere.materialIndex), [9])
    XCTAssertTrue(all.planes.isEmpty)
  }

  /// `SceneObject` dispatches to the object it holds.
  func testSceneObject_Dispatches() {
    let sphere = Sphere<Double>(center: Vector3(0, 0, -10), radius: 2)
    let plane = Plane<Double>(normal: Vector3(0, 0, 1), offset: -3)
    let ray = Ray<Double>(origin: .zero, direction: Vector3(0, 0, -1))
    XCTAssertEqual(
      SceneObject.sphere(sphere).intersect(ray, after: 0, before: .infinity),
      sphere.intersect(ray, after: 0, before: .infinity))
    XCTAssertEqual(
      SceneObject.plane(plane).intersect(ray, after: 0, before: .infinity)?.t, 3
    )
    XCTAssertEqual(
      SceneObject.group(Group([.sphere(sphere)])).intersect(
        ray, after: 0, before: .infinity)?.t, 8)
  }

  /// A large group flattened by several threads (its own spheres read in
  /// parts) is the group flattened by one, with planes, meshes and
  /// transformed spheres among the spheres; and a nested group of spheres
  /// among them keeps its place (the walk in order).
  func testFlattened_InPartsAsInOrder() throws {
    var random = SplitMix64(seed: 9)
    func next() -> Double { Double(random.next() >> 11) * 0x1p-53 }
    var objects: [SceneObject<Double>] = []
    for index in 0..<70_000 {
      objects.append(
        .sphere(
          Sphere(
            center: Vector3(next(), next(), next()), radius: next() + 0.1,
            materialIndex: index % 5)))
      if index % 9_999 == 0 {
        objects.append(
          .plane(Plane(normal: Vector3(0, 1, 0), offset: next())))
        objects.append(
          .triangle(
            Triangle(Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0))))
      }
    }
    func same(_ group: Group<Double>, _ note: String) {
      let (one, parts) = (group.flattened(), group.flattened(threads: 3))
      XCTAssertEqual(one.spheres, parts.spheres, note)
      XCTAssertEqual(one.planes, parts.planes, note)
      XCTAssertEqual(one.triangles.count, parts.triangles.count, note)
      XCTAssertEqual(
        one.transformedSpheres, parts.transformedSpheres, note)
    }
    same(Group(objects), "spheres, planes and triangles")
    var nested = objects
    nested.insert(
      .group(Group([.sphere(Sphere(center: .zero, radius: 2))])), at: 30_000)
    same(Group(nested), "a group of spheres among them")
    var stretched = objects
    let stretch = try XCTUnwrap(
      Transform(
        matrix: .scale(Vector3(1, 2, 3)),
        object: .sphere(Sphere(center: .zero, radius: 1))))
    stretched.insert(.transform(stretch), at: 50_000)
    same(Group(stretched), "a stretched sphere among them")
  }

  /// A group's entry is no bigger than a sphere and its tag: every larger
  /// payload is boxed (a mesh inline made the entries of 10⁶ spheres
  /// 84 MiB, not 46, each page zeroed by the kernel as the parse wrote it).
  func testEntryIsNoBiggerThanASphere() {
    func check<T: RayScalar>(_: T.Type) {
      let entry = MemoryLayout<SceneObject<T>>.stride
      let alignment = MemoryLayout<SceneObject<T>>.alignment
      let sphereAndTag = MemoryLayout<Sphere<T>>.size + 1
      let rounded = (sphereAndTag + alignment - 1) / alignment * alignment
      XCTAssertEqual(entry, rounded, "\(T.self)")
    }
    check(Float.self)
    check(Double.self)
  }
}

extension SceneObject {
  /// A short name for messages.
  fileprivate var kind: String {
    switch self {
    case .sphere: "sphere"
    case .plane: "plane"
    case .group: "group"
    case .triangle: "triangle"
    case .mesh: "mesh"
    case .transform: "transform"
    case .shape: "shape"
    }
  }
}
