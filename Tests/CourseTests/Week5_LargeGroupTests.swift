import Geometry
import SceneDescription
import XCTest

@testable import Course

/// Week 5, triangles and meshes: a group of many objects is held in a
/// hierarchy of boxes (`BoxedGroup`, given, not written by the student),
/// as a mesh's triangles are, and finds exactly what the list's loop
/// (`Group.intersect`, week 1) finds, ties included.
final class Week5_LargeGroupTests: XCTestCase {
  func testBoxedGroup_FindsWhatTheListFinds() {
    var generator = SplitMix64(seed: 11)
    func random(_ range: ClosedRange<Double>) -> Double {
      .random(in: range, using: &generator)
    }
    var objects: [any Hittable] = (0..<300).map { index in
      Sphere(
        center: Vector3(random(-10...10), random(-10...10), random(-10...10)),
        radius: random(0.2...1.5), materialIndex: index % 7)
    }
    // The same sphere listed twice, a tie at every hit that the first
    // listed must win; the second in a group with a plane far away, so
    // that it has no box and is asked before the hierarchy's objects.
    objects.insert(
      Sphere(center: Vector3(0, 0, 0), radius: 2, materialIndex: 8), at: 5)
    objects.append(
      Group([
        Sphere(center: Vector3(0, 0, 0), radius: 2, materialIndex: 9),
        Plane(normal: Vector3(0, 1, 0), offset: -1000, materialIndex: 11),
      ]))
    objects.append(
      Plane(normal: Vector3(0, 1, 0), offset: -11, materialIndex: 10))
    let list = Group(objects)
    let boxed = BoxedGroup(objects)
    var (hits, twins) = (0, 0)
    for index in 0..<3000 {
      let origin = Vector3(random(-15...15), random(-15...15), random(-15...15))
      // One ray in five aimed near the twins at the origin.
      let toward = index % 5 == 0 ? origin * -0.1 : .zero
      let direction =
        (Vector3(random(-1...1), random(-1...1), random(-1...1)) + toward)
        .normalized()
      let ray = Ray(origin: origin, direction: direction)
      let want = list.intersect(ray, after: 0, before: .infinity)
      let got = boxed.intersect(ray, after: 0, before: .infinity)
      XCTAssertEqual(got?.t, want?.t, "\(ray)")
      XCTAssertEqual(got?.normal, want?.normal, "\(ray)")
      XCTAssertEqual(got?.materialIndex, want?.materialIndex, "\(ray)")
      if want != nil { hits += 1 }
      XCTAssertNotEqual(got?.materialIndex, 9, "the later twin never wins")
      if got?.materialIndex == 8 { twins += 1 }
    }
    XCTAssertGreaterThan(hits, 1000)
    XCTAssertGreaterThan(twins, 10, "rays meet the twins")
    XCTAssertNil(boxed.boundingBox, "a plane has no box")
  }

  /// The readers' groups of more than `BoxedGroup.threshold` objects are
  /// held in one; smaller ones stay the plain list a student reads.
  func testLargeGroupsOnly_AreBoxed() {
    func group(_ count: Int) -> Course.Group {
      SceneObjects.group(
        SceneDescription.Group(
          (0..<count).map { index in
            .sphere(
              SceneDescription.Sphere(
                center: Vector3(Double(index), 0, 0), radius: 0.4))
          }))
    }
    XCTAssertEqual(group(BoxedGroup.threshold).objects.count, 16)
    XCTAssertTrue(group(BoxedGroup.threshold).objects.first is Sphere)
    let large = group(BoxedGroup.threshold + 1)
    XCTAssertEqual(large.objects.count, 1)
    XCTAssertEqual((large.objects.first as? BoxedGroup)?.objects.count, 17)
  }
}
