import XCTest

@testable import FastEngine
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

extension ScreenTilesTests {
  /// Spheres whose silhouettes pass within 64 ε of Float of the exact ray
  /// through a random pixel centre, inside or outside, at distances and
  /// sizes over many binades: where the kernels' rounding decides hit or
  /// miss, so a box computed for the bare radius would lose pixels.
  func grazingSpheres(
    _ generator: inout SplitMix64, camera: PerspectiveCamera<Double>,
    style: ImageStyle,
    width: Int, height: Int, count: Int
  ) -> [Sphere<Double>] {
    let aspect = Double(height) / Double(width)
    return (0..<count).map { _ in
      let screen = ScreenMap(style: style, width: width, height: height)
      let x: Double = screen.x(
        column: Int.random(in: 0..<width, using: &generator))
      let y: Double = screen.y(
        row: Int.random(in: 0..<height, using: &generator))
      let direction = styled(camera, style).rayDirection(
        x: x, y: y, aspect: aspect
      ).normalized()
      let across = direction.cross(generator.unitVector(Double.self))
        .normalized()
      let distance: Double = generator.logUniform(1e-2, 1e7)
      let radius = distance * generator.logUniform(1e-7, 0.5)
      let miss =
        1 + Double.random(in: -64...64, using: &generator)
        * Double(Float.ulpOfOne)
      return Sphere(
        center: camera.center + direction * distance + across * (radius * miss),
        radius: radius)
    }
  }

  /// The property the images rest on, sphere by sphere and without the
  /// help of nearer spheres hiding a mistake: every pixel whose ray the
  /// kernel reports hitting the sphere is in the sphere's box.
  func checkBoxesHoldEveryHit<Kernel: IntersectionKernel>(
    _: Kernel.Type, base: UInt64
  ) {
    forEachSeed(Self.seedCount(10), base: base) { generator, _ in
      guard var scene = randomScene(&generator, count: 60) else { return }
      let (width, height) = (33, 27)
      for style in ImageStyle.allCases {
        let grazing = grazingSpheres(
          &generator, camera: scene.camera, style: style, width: width,
          height: height, count: 60)
        scene.root = Group(scene.root.objects + grazing.map { .sphere($0) })
      }
      let compiled = CompiledScene<Kernel>(scene, projectionThreshold: 0)
      for style in ImageStyle.allCases {
        let camera = styled(compiled.camera, style)
        let screen = ScreenMap(style: style, width: width, height: height)
        let projection = ScreenProjection(
          camera: PerspectiveCamera<Double>(camera), screen: screen)
        let aspect = Kernel.Scalar(height) / Kernel.Scalar(width)
        var (outside, hits) = (0, 0)
        for record in compiled.spheres {
          let (center, reach) = compiled.cullBound(record)
          let box = projection.pixelBox(center: center, reach: reach)
          for row in 0..<height {
            let y: Kernel.Scalar = screen.y(row: row)
            for column in 0..<width {
              let x: Kernel.Scalar = screen.x(column: column)
              let ray = CameraRay(
                origin: compiled.rayOrigin,
                direction: camera.rayDirection(
                  x: x, rowBase: camera.rowBase(y: y, aspect: aspect)))
              guard Kernel.intersect(record, ray, before: .infinity) != nil
              else { continue }
              hits += 1
              if box.isEmpty || !box.columns.contains(column)
                || !box.rows.contains(row)
              {
                outside += 1
              }
            }
          }
        }
        XCTAssertGreaterThan(hits, 0)
        XCTAssertEqual(
          outside, 0, "\(Kernel.self) \(style): hits outside their sphere's box"
        )
      }
    }
  }

  func testBoxes_HoldEveryHit_StableDouble() throws {
    try skipUnlessLongTests()
    checkBoxesHoldEveryHit(StableKernel<Double>.self, base: 0xB01)
  }

  func testBoxes_HoldEveryHit_StableFloat() throws {
    try skipUnlessLongTests()
    checkBoxesHoldEveryHit(StableKernel<Float>.self, base: 0xB02)
  }

  func testBoxes_HoldEveryHit_NaiveFloat() throws {
    try skipUnlessLongTests()
    checkBoxesHoldEveryHit(NaiveKernel<Float>.self, base: 0xB03)
  }

  /// Boxes are tight where nothing is extreme: a sphere seen head-on at
  /// the centre of the image gets the pixels whose centres its silhouette's
  /// box holds, not one more.
  func testBox_IsTightForAnOrdinarySphere() {
    guard
      let camera = PerspectiveCamera<Double>(
        center: .zero, direction: Vector3(0, 0, -1), up: Vector3(0, 1, 0),
        angle: 90)
    else { return XCTFail("camera") }
    let projection = ScreenProjection(
      camera: camera,
      screen: ScreenMap(style: .course, width: 100, height: 100))
    // Radius 0.1 at distance 10: the silhouette spans tan(asin(0.01)) =
    // 0.0100005 either side of the centre, 0.500025 pixel at 50 pixels per
    // screen unit, about the centre at column 49.5: columns 49 and 50; the
    // course's rows sample one pixel higher, so y = 0 is row 50.5: rows 50
    // and 51.
    let box = projection.pixelBox(center: Vector3(0, 0, -10), reach: 0.1)
    XCTAssertEqual(
      box, PixelBox(firstColumn: 49, lastColumn: 50, firstRow: 50, lastRow: 51))
    // 0.49 pixel either side of 49.5 holds no pixel centre: no pixel.
    let smaller = projection.pixelBox(center: Vector3(0, 0, -10), reach: 0.098)
    XCTAssertTrue(smaller.isEmpty, "\(smaller)")
    // Behind the eye: no pixel. Straddling the eye's plane: every pixel.
    XCTAssertTrue(
      projection.pixelBox(center: Vector3(0, 0, 10), reach: 1).isEmpty)
    XCTAssertEqual(
      projection.pixelBox(center: Vector3(5, 0, 0.5), reach: 1),
      projection.whole)
  }
}
