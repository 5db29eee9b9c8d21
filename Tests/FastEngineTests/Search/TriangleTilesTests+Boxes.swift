import XCTest

@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension TriangleTilesTests {
  /// The large triangles' own hierarchy (`buildLargeTriangleHierarchy`)
  /// answers as testing each in order does, for rays through their
  /// corners and edges, each moved by up to 64 ulps of its coordinates'
  /// size: where the test's rounding decides at the edge of the box, so
  /// that boxes of the bare triangles would lose hits.
  func checkLargeTriangleBoxes<Kernel: IntersectionKernel>(
    _: Kernel.Type, base: UInt64
  ) {
    typealias S = Kernel.Scalar
    forEachSeed(Self.seedCount(10), base: base) { generator, _ in
      guard let scene = randomScene(&generator, largeTriangles: 30) else {
        return
      }
      let tree = CompiledScene<Kernel>(
        scene, hierarchyThreshold: 0, triangleProjectionThreshold: .max)
      XCTAssertNotNil(tree.largeTriangleHierarchy)
      var each = tree
      each.largeTriangleHierarchy = nil
      var hits = 0
      for index in tree.ordinaryTriangleCount..<tree.triangles.count {
        let record = tree.triangles[index]
        let corners = [record.v0, record.v1, record.v2]
        for _ in 0..<40 {
          let a = Int.random(in: 0..<3, using: &generator)
          let along = S(Double.random(in: 0...1, using: &generator))
          let edge =
            Bool.random(using: &generator)
            ? corners[a]
            : corners[a] + (corners[(a + 1) % 3] - corners[a]) * along
          let ulps = S.ulpOfOne * edge.maxMagnitude
          let jitter = Vector3(
            S(Double.random(in: -64...64, using: &generator)),
            S(Double.random(in: -64...64, using: &generator)),
            S(Double.random(in: -64...64, using: &generator)))
          let direction = (edge + jitter * ulps - tree.rayOrigin).normalized()
          let ray = CameraRay(origin: tree.rayOrigin, direction: direction)
          let prepared = WatertightRay(
            Ray(origin: ray.origin, direction: ray.direction))
          var found = NearestHit<S, CompiledScene<Kernel>.Nearest>(
            before: .infinity)
          tree.testLargeTriangles(ray, prepared, &found)
          var expected = NearestHit<S, CompiledScene<Kernel>.Nearest>(
            before: .infinity)
          each.testLargeTriangles(ray, prepared, &expected)
          XCTAssertEqual(found.hit?.t, expected.hit?.t, "\(Kernel.self)")
          // The triangle aimed at: its box entered by every ray it
          // reports hitting, at or before the hit, by the binary
          // hierarchy's slab test (the wide one's Float boxes are wider).
          let direct = withUnsafePointer(to: record) {
            TriangleRecord.t(
              prepared, $0,
              plane: tree.trianglePlanes[index - tree.ordinaryTriangleCount],
              before: .infinity)
          }
          if let direct {
            hits += 1
            let box = CompiledScene<Kernel>.largeTriangleBox(record)
            let node = BoundingVolumeHierarchy<S>.Node(
              lower: box.lower, upper: box.upper, index: 0, count: 1)
            XCTAssertNotNil(
              BoundingVolumeHierarchy<S>.Slab(ray).entry(node, before: direct),
              "\(Kernel.self): triangle \(index) hit outside its box")
          }
          if case .triangle(let f)? = found.hit?.what,
            case .triangle(let e)? = expected.hit?.what
          {
            XCTAssertEqual(f, e, "\(Kernel.self)")
          }
        }
      }
      XCTAssertGreaterThan(hits, 0)
    }
  }

  func testLargeTriangleBoxes_StableDouble() {
    checkLargeTriangleBoxes(StableKernel<Double>.self, base: 0x7A7)
  }
  func testLargeTriangleBoxes_StableFloat() {
    checkLargeTriangleBoxes(StableKernel<Float>.self, base: 0x7A8)
  }

  /// Triangles whose corner extreme on the screen (left or right, top or
  /// bottom) lies within 64 ulps of its coordinates' size (in Float) of
  /// the exact ray through a random pixel centre, inside or outside, at
  /// distances and sizes over many binades, in scenes anywhere from the
  /// origin: where the watertight test's rounding decides hit or miss at
  /// the edge of the box, so a box for the bare triangle would lose pixels.
  func grazingTriangles(
    _ generator: inout SplitMix64, camera: PerspectiveCamera<Double>,
    style: ImageStyle, width: Int, height: Int, count: Int
  ) -> [Triangle<Double>] {
    let aspect = Double(height) / Double(width)
    let view = styled(camera, style)
    return (0..<count).map { _ in
      let screen = ScreenMap(style: style, width: width, height: height)
      let x: Double = screen.x(
        column: Int.random(in: 0..<width, using: &generator))
      let y: Double = screen.y(
        row: Int.random(in: 0..<height, using: &generator))
      let direction = view.rayDirection(x: x, y: y, aspect: aspect)
        .normalized()
      // Screen right and up at that pixel, perpendicular to its ray, each
      // flipped at random so the corner is extreme on either side.
      let right =
        (view.horizontal - direction * view.horizontal.dot(direction))
        .normalized() * generator.sign()
      let up = direction.cross(right) * generator.sign()
      let distance: Double = generator.logUniform(1e-2, 1e7)
      let point = camera.center + direction * distance
      let size = distance * generator.logUniform(1e-7, 0.5)
      let ulps = Double(Float.ulpOfOne) * point.maxMagnitude
      let corner =
        point + right * (Double.random(in: -64...64, using: &generator) * ulps)
        + up * (Double.random(in: -64...64, using: &generator) * ulps)
      return Triangle(
        corner, corner + right * size + up * (0.3 * size),
        corner + right * (0.3 * size) + up * size, materialIndex: 0)
    }
  }

  /// The property the images rest on, triangle by triangle: every pixel
  /// whose ray the watertight test reports hitting the triangle lies in its
  /// box, grazing triangles (`grazingTriangles`) among them.
  func checkBoxesHoldEveryHit<Kernel: IntersectionKernel>(
    _: Kernel.Type, base: UInt64
  ) {
    forEachSeed(Self.seedCount(10), base: base) { generator, _ in
      guard var scene = randomScene(&generator) else { return }
      let (width, height) = (33, 27)
      for style in ImageStyle.allCases {
        let grazing = grazingTriangles(
          &generator, camera: scene.camera, style: style, width: width,
          height: height, count: 60)
        scene.root = Group(scene.root.objects + grazing.map { .triangle($0) })
      }
      let compiled = CompiledScene<Kernel>(
        scene, triangleProjectionThreshold: 0)
      for style in ImageStyle.allCases {
        let camera = styled(compiled.camera, style)
        let screen = ScreenMap(style: style, width: width, height: height)
        let projection = ScreenProjection(
          camera: PerspectiveCamera<Double>(camera), screen: screen)
        let aspect = Kernel.Scalar(height) / Kernel.Scalar(width)
        for (index, record) in compiled.triangles.enumerated() {
          let box = compiled.triangleBox(record, projection, margin: 0)
          let plane =
            index < compiled.ordinaryTriangleCount
            ? nil
            : compiled.trianglePlanes[index - compiled.ordinaryTriangleCount]
          for row in 0..<height {
            for column in 0..<width {
              let x: Kernel.Scalar = screen.x(column: column)
              let y: Kernel.Scalar = screen.y(row: row)
              let direction = camera.rayDirection(x: x, y: y, aspect: aspect)
              let ray = WatertightRay(
                Ray(origin: compiled.rayOrigin, direction: direction))
              let t: Kernel.Scalar? =
                if let plane {
                  withUnsafePointer(to: record) {
                    TriangleRecord.t(ray, $0, plane: plane, before: .infinity)
                  }
                } else {
                  record.intersect(ray, before: .infinity)?.t
                }
              guard t != nil else { continue }
              let inside =
                !box.isEmpty && box.columns.contains(column)
                && box.rows.contains(row)
              XCTAssertTrue(
                inside,
                "\(Kernel.self) \(style): triangle \(index) hit at "
                  + "(\(column), \(row)) outside its box \(box)")
            }
          }
        }
      }
    }
  }

  func testBoxesHoldEveryHit_StableDouble() throws {
    try skipUnlessLongTests()
    checkBoxesHoldEveryHit(StableKernel<Double>.self, base: 0x7B1)
  }
  func testBoxesHoldEveryHit_NaiveFloat() throws {
    try skipUnlessLongTests()
    checkBoxesHoldEveryHit(NaiveKernel<Float>.self, base: 0x7B2)
  }
  func testBoxesHoldEveryHit_StableFloat() throws {
    try skipUnlessLongTests()
    checkBoxesHoldEveryHit(StableKernel<Float>.self, base: 0x7B3)
  }
}
