import FastKernels
import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

/// The course's property-list schema: every object and transform against
/// the same scene in the text format, resources by name, and the errors
/// with their exact messages.
final class PlistSceneReaderTests: XCTestCase {
  var folder = ""

  override func setUpWithError() throws {
    folder = NSTemporaryDirectory() + "plist-tests-\(UUID().uuidString)"
    for sub in ["Meshes", "Textures"] {
      try FileManager.default.createDirectory(
        atPath: "\(folder)/\(sub)", withIntermediateDirectories: true)
    }
    try "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"
      .write(
        toFile: "\(folder)/Meshes/tri.obj", atomically: true, encoding: .utf8)
    try "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
      .write(
        toFile: "\(folder)/Meshes/plain.obj", atomically: true, encoding: .utf8)
  }

  override func tearDownWithError() throws {
    try? FileManager.default.removeItem(atPath: folder)
  }

  /// A property list whose top-level dictionary holds `body`.
  func plist(_ body: String) -> [UInt8] {
    Array(
      ("""
      <?xml version="1.0" encoding="UTF-8"?>
      <plist version="1.0">
      <dict>
      \(body)
      </dict>
      </plist>
      """).utf8)
  }

  static let camera = Fixtures.plistCamera

  func read(_ body: String) throws(SceneError) -> Scene {
    try SceneReader.parse(bytes: plist(body), file: "\(folder)/s.plist")
  }

  func assertError(
    _ body: String, _ message: String,
    file: StaticString = #filePath, line: UInt = #line
  ) {
    XCTAssertThrowsError(try read(body), file: file, line: line) { error in
      XCTAssertEqual(
        (error as? SceneError)?.description,
        "\(folder)/s.plist: error: \(message)", file: file, line: line)
    }
  }

  /// Every object type, every transform operation, lights, background and
  /// materials, read into the same model as the same scene in text.
  func testEveryObjectAndTransform_MatchesTheTextFormat() throws {
    let scene = try read(
      Self.camera + """
        <key>Lights</key><array>
          <dict><key>type</key><string>PointLight</string>
            <key>position</key><string>1 2 3</string>
            <key>color</key><string>0.5 0.5 0.5</string>
            <key>falloff</key><string>0.25</string></dict>
          <dict><key>type</key><string>DirectionalLight</string>
            <key>direction</key><string>0 -1 -1</string>
            <key>color</key><string>1 1 1</string></dict></array>
        <key>Background</key><dict><key>color</key><string>0.1 0.2 0.3</string>
          <key>ambientLight</key><string>0.2 0.2 0.2</string></dict>
        <key>Materials</key><array>
          <dict><key>type</key><string>PhongMaterial</string>
            <key>diffuseColor</key><string>1 0 0</string>
            <key>specularColor</key><string>1 1 1</string>
            <key>shininess</key><string>10</string></dict>
          <dict><key>diffuseColor</key><string>0 1 0</string></dict></array>
        <key>Group</key><array>
          <dict><key>type</key><string>Sphere</string>
            <key>materialIndex</key><string>1</string>
            <key>center</key><string>0 0 0</string><key>radius</key>\
            <real>1.5</real></dict>
          <dict><key>type</key><string>Plane</string>
            <key>normal</key><string>0 1 0</string><key>offset</key>\
            <string>2</string></dict>
          <dict><key>type</key><string>Triangle</string>
            <key>materialIndex</key><string>1</string>
            <key>vertex0</key><string>0 0 0</string>
            <key>vertex1</key><string>1 0 0</string>
            <key>vertex2</key><string>0 1 0</string></dict>
          <dict><key>type</key><string>Group</string><key>Group</key><array>
            <dict><key>type</key><string>TriangleMesh</string>
              <key>objFile</key><string>plain</string></dict></array></dict>
          <dict><key>type</key><string>Transform</string>
            <key>materialIndex</key><string>1</string>
            <key>transforms</key><array>
              <string>translate 1 2 3</string><string>scale 1 2 3</string>
              <string>uniformScale 2</string><string>xRotate 10</string>
              <string>yRotate 20</string><string>zRotate 30</string>
              <string>rotate 1 1 0 45</string></array>
            <key>transformed</key><dict><key>type</key><string>Sphere</string>
              <key>materialIndex</key><string>0</string>
              <key>center</key><string>0 0 0</string>
              <key>radius</key><string>1</string></dict></dict>
        </array>
        """)
    let text = try SceneParser.parse(
      """
      PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
      Lights { numLights 2
        PointLight { position 1 2 3 color 0.5 0.5 0.5 falloff 0.25 }
        DirectionalLight { direction 0 -1 -1 color 1 1 1 } }
      Background { color 0.1 0.2 0.3 ambientLight 0.2 0.2 0.2 }
      Materials { numMaterials 2
        PhongMaterial { diffuseColor 1 0 0 specularColor 1 1 1 shininess 10 }
        Material { diffuseColor 0 1 0 } }
      Group { numObjects 5
        MaterialIndex 1 Sphere { center 0 0 0 radius 1.5 }
        MaterialIndex 0 Plane { normal 0 1 0 offset -2 }
        MaterialIndex 1 Triangle { vertex0 0 0 0 vertex1 1 0 0 vertex2 0 1 0 }
        MaterialIndex 0 Group { numObjects 1
          TriangleMesh { obj_file Meshes/plain.obj } }
        MaterialIndex 1 Transform { Translate 1 2 3 Scale 1 2 3 UniformScale 2
          XRotate 10 YRotate 20 ZRotate 30 Rotate 1 1 0 45
          Sphere { center 0 0 0 radius 1 } } }
      """, file: "\(folder)/s.txt")
    XCTAssertEqual(scene.camera, text.camera)
    XCTAssertEqual(scene.lights, text.lights)
    XCTAssertEqual(scene.background, text.background)
    XCTAssertEqual(scene.ambient, text.ambient)
    XCTAssertEqual(scene.materials, text.materials)
    XCTAssertEqual(scene.root, text.root)
  }

  /// Defaults: diffuse white, no specular; objects without an index take
  /// their group's, or 0; a Transform's index is its object's.
  func testDefaultsAndMaterialIndices() throws {
    let scene = try read(
      Self.camera + """
        <key>Materials</key><array><dict/><dict/><dict/></array>
        <key>Group</key><array>
          <dict><key>type</key><string>Group</string>
            <key>materialIndex</key><string>2</string>
            <key>Group</key><array>
            <dict><key>type</key><string>Sphere</string>
              <key>center</key><string>0 0 0</string>
              <key>radius</key><string>1</string></dict></array></dict>
          <dict><key>type</key><string>Sphere</string>
            <key>center</key><string>0 0 0</string>
            <key>radius</key><string>1</string></dict></array>
        """)
    XCTAssertEqual(scene.materials[0], Material(diffuse: Vector3(1, 1, 1)))
    let all = scene.root.flattened()
    XCTAssertEqual(all.spheres.map(\.materialIndex), [2, 0])
  }

  /// `objFile NAME` is Meshes/NAME.obj and `texture NAME` is
  /// Textures/NAME.bmp beside the scene; a missing one names the paths
  /// tried.
  func testResourcesByName() throws {
    try Data(BMPReaderTests.bmp(BMPReaderTests.image))
      .write(to: URL(fileURLWithPath: "\(folder)/Textures/wood.bmp"))
    let scene = try read(
      Self.camera + """
        <key>Materials</key><array><dict><key>texture</key>\
        <string>wood</string></dict></array>
        <key>Group</key><array><dict><key>type</key>\
        <string>TriangleMesh</string>
          <key>objFile</key><string>tri</string></dict></array>
        """)
    XCTAssertEqual(
      scene.materials[0].texturePath, "\(folder)/Textures/wood.bmp")
    XCTAssertEqual(scene.root.flattened().triangles.count, 1)
    assertError(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key>"
        + "<string>TriangleMesh</string>"
        + "<key>objFile</key><string>gone</string></dict></array>",
      "Group[0].objFile: no file for \"gone\"; tried "
        + "'\(folder)/Meshes/gone.obj', '\(folder)/gone.obj'")
    assertError(
      Self.camera
        + "<key>Materials</key><array><dict><key>texture</key>"
        + "<string>gone</string>"
        + "</dict></array><key>Group</key><array/>",
      "Materials[0].texture: no file for \"gone\"; tried "
        + "'\(folder)/Textures/gone.bmp', '\(folder)/gone.bmp'")
  }

  /// A textured material on a mesh without texture coordinates is an
  /// error at the mesh.
  func testTexturedMeshNeedsTextureCoordinates() throws {
    try Data(BMPReaderTests.bmp(BMPReaderTests.image))
      .write(to: URL(fileURLWithPath: "\(folder)/Textures/wood.bmp"))
    assertError(
      Self.camera + """
        <key>Materials</key><array><dict><key>texture</key>\
        <string>wood</string></dict></array>
        <key>Group</key><array><dict><key>type</key>\
        <string>TriangleMesh</string>
          <key>objFile</key><string>plain</string></dict></array>
        """,
      "Group[0].objFile: material 0 has a texture, but the mesh "
        + "'\(folder)/Meshes/plain.obj' has no texture coordinates (no face "
        + "gives vt)"
    )
  }

  func testErrors_KeyPaths() {
    assertError(
      Self.camera
        + "<key>Materials</key><array><dict/><dict/><dict>"
        + "<key>diffuseColor</key><string>0.2 0.8</string></dict></array>"
        + "<key>Group</key><array/>",
      "Materials[2].diffuseColor: expected 3 numbers, found \"0.2 0.8\"")
    assertError(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key><string>Sphere</string>"
        + "<key>center</key><string>0 0 x</string>"
        + "<key>radius</key><string>1</string></dict></array>",
      "Group[0].center: expected 3 numbers (finite, decimal), found \"0 0 x\"")
    assertError(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key><string>Sphere</string>"
        + "<key>center</key><string>0 0 0</string>"
        + "<key>radius</key><string>-1</string></dict></array>",
      "Group[0].radius: 'radius' must be positive, found \"-1\"")
    assertError(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key><string>Spere</string>"
        + "</dict></array>",
      "Group[0].type: unknown type \"Spere\"; expected Sphere, Plane, "
        + "Triangle, TriangleMesh, Group, Transform; did you mean 'Sphere'?")
    assertError(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key>"
        + "<string>Transform</string>"
        + "<key>transforms</key><array><string>translat 1 2 3</string></array>"
        + "<key>transformed</key><dict/></dict></array>",
      "Group[0].transforms[0]: unknown transform \"translat\"; expected one "
        + "of translate, scale, uniformScale, xRotate, yRotate, zRotate, "
        + "rotate; did you mean 'translate'?")
    assertError(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key>"
        + "<string>Transform</string>"
        + "<key>transforms</key><array><string>rotate 0 0 0 30</string></array>"
        + "<key>transformed</key><dict/></dict></array>",
      "Group[0].transforms[0]: 'rotate' needs a non-zero axis")
    assertError(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key><string>Sphere</string>"
        + "<key>materialIndex</key><string>3</string>"
        + "<key>center</key><string>0 0 0</string>"
        + "<key>radius</key><string>1</string></dict></array>",
      "Group[0].materialIndex: materialIndex \"3\" is out of range: the scene "
        + "has no materials (only the default, 0)")
    assertError(
      Self.camera + "<key>Lihgts</key><array/><key>Group</key><array/>",
      "Lihgts: unknown key; expected Camera, Lights, Background, Materials, "
        + "Group; did you mean 'Lights'?")
    assertError("<key>Group</key><array/>", "the scene has no Camera")
    assertError(
      Self.camera + "<key>Group</key><dict/>",
      "Group: expected an array, found a dictionary")
    assertError(
      Self.camera
        + "<key>Background</key><dict><key>color</key><string>1e999 0 "
        + "0</string>"
        + "</dict><key>Group</key><array/>",
      "Background.color: '1e999' is beyond the finite range of double "
        + "(±1.7976931348623157e+308)"
    )
  }

  /// Nesting beyond the text format's limit is refused by key path, and a
  /// list nested past what any scene needs before it is decoded at all.
  func testErrors_Nesting() {
    var object =
      "<dict><key>type</key><string>Sphere</string>"
      + "<key>center</key><string>0 0 0</string><key>radius</key>"
      + "<string>1</string></dict>"
    for _ in 0..<SceneParser.maximumGroupDepth {
      object =
        "<dict><key>type</key><string>Group</string><key>Group</key><array>"
        + object + "</array></dict>"
    }
    XCTAssertThrowsError(
      try read(Self.camera + "<key>Group</key><array>\(object)</array>")
    ) { error in
      XCTAssertTrue(
        (error as? SceneError)?.message.hasSuffix(
          "Groups and Transforms are nested more than 200 deep") ?? false,
        "\(error)")
    }
    let deep =
      String(repeating: "<array>", count: 100_000)
      + String(repeating: "</array>", count: 100_000)
    XCTAssertThrowsError(
      try read(Self.camera + "<key>Group</key>\(deep)")
    ) { error in
      XCTAssertEqual(
        (error as? SceneError)?.message,
        "the property list is nested more than 816 levels deep")
    }
  }

  /// A binary list nested deeper than any scene needs is refused before
  /// the decoder (which recurses per level) sees it; a cut-off one is an
  /// error, never a trap.
  func testErrors_BinaryNesting() throws {
    var value: Any = "leaf"
    for _ in 0..<2_000 { value = [value] }
    let binary = try PropertyListSerialization.data(
      fromPropertyList: ["Camera": value], format: .binary, options: 0)
    XCTAssertThrowsError(
      try SceneReader.parse(bytes: Array(binary), file: "deep.plist")
    ) { error in
      XCTAssertEqual(
        (error as? SceneError)?.description,
        "deep.plist: error: the property list is nested more than 816 "
          + "levels deep")
    }
    XCTAssertEqual(PropertyList.binaryShape(Array(binary))?.depth, 817)
    for cut in stride(from: 8, to: binary.count, by: 97) {
      XCTAssertThrowsError(
        try SceneReader.parse(bytes: Array(binary.prefix(cut)), file: "c"))
    }
  }

  /// Malformed XML: the decoder's reason, at its line.
  func testErrors_MalformedXML() {
    XCTAssertThrowsError(
      try SceneReader.parse(
        bytes: Array(
          ("<?xml version=\"1.0\"?>\n<plist>\n<dict>\n<key>a</key>\n"
            + "<strin>x</string>\n").utf8),
        file: "bad.plist")
    ) { error in
      let description = (error as? SceneError)?.description ?? ""
      XCTAssertTrue(
        description.hasPrefix("bad.plist:")
          && description.contains(
            "error: not a valid property list"),
        description)
      XCTAssertFalse(description.contains("\n"))
    }
  }

  /// Binary property lists read as XML ones do.
  func testBinary() throws {
    let xml = plist(
      Self.camera
        + "<key>Group</key><array><dict><key>type</key><string>Sphere</string>"
        + "<key>center</key><string>0 0 0</string><key>radius</key>"
        + "<string>1</string></dict></array>"
    )
    let tree = try PropertyListSerialization.propertyList(
      from: Data(xml), format: nil)
    let binary = try PropertyListSerialization.data(
      fromPropertyList: tree, format: .binary, options: 0)
    XCTAssertTrue(binary.starts(with: Array("bplist".utf8)))
    let scene = try SceneReader.parse(bytes: Array(binary), file: "b.plist")
    XCTAssertEqual(
      scene.root, try SceneReader.parse(bytes: xml, file: "x.plist").root)
  }
}
