import Foundation
import XCTest

@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport
import TestSupport

extension SceneParserTests {
  /// Malformed fields, numbers, cameras, material indices, ends of file
  /// and nesting.
  static let malformedValues: [Malformed] = {
    let c = SceneParserTests.camera
    let g = SceneParserTests.group
    let s = SceneParserTests.sphere
    return [
      // Fields.
      Malformed(
        name: "missing field",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 } }",
        line: 2, column: 44, message: "Sphere is missing 'radius'"),
      Malformed(
        name: "missing fields",
        text: "PerspectiveCamera {\n center 0 0 0\n up 0 1 0\n}\n" + g, line: 4,
        column: 1,
        message: "PerspectiveCamera is missing 'direction' and 'angle'"),
      Malformed(
        name: "missing diffuse colour",
        text: c + "Materials { numMaterials 1 PhongMaterial { shininess 3 } }",
        line: 2, column: 56,
        message: "PhongMaterial is missing 'diffuseColor'"),
      Malformed(
        name: "missing light colour",
        text: c + "Lights { numLights 1 PointLight { position 0 0 0 } }",
        line: 2, column: 50, message: "PointLight is missing 'color'"),
      Malformed(
        name: "field given twice",
        text: c
          + "Group { numObjects 1 Sphere { radius 1 center 0 0 0 radius 2 } }",
        line: 2, column: 53, message: "'radius' is given twice in Sphere"),
      Malformed(
        name: "duplicate camera field",
        text: "PerspectiveCamera { angle 30 angle 40 }", line: 1, column: 30,
        message: "'angle' is given twice in PerspectiveCamera"),
      Malformed(
        name: "unknown field with suggestion",
        text: c + "Group { numObjects 1 Sphere { centre 0 0 0 radius 1 } }",
        line: 2, column: 31,
        message:
          "expected a field of Sphere, found 'centre'; did you mean 'center'?"),
      Malformed(
        name: "unknown light with suggestion",
        text: c + "Lights { numLights 1 SpotLight { } }", line: 2, column: 22,
        message:
          "expected a light, found 'SpotLight'; did you mean 'PointLight'?"),
      Malformed(
        name: "object among the lights",
        text: c + "Lights { numLights 1 \(s) }", line: 2, column: 22,
        message: "expected a light, found 'Sphere' (expected one of "
          + "'PointLight', 'DirectionalLight')"),
      Malformed(
        name: "unknown material with suggestion",
        text: c + "Materials { numMaterials 1 PhongMaterail { } }", line: 2,
        column: 28,
        message:
          "expected a material, found 'PhongMaterail'; did you mean "
            + "'PhongMaterial'?"
      ),
      Malformed(
        name: "number for an object", text: c + "Group { numObjects 1 5 }",
        line: 2, column: 22, message: "expected an object, found the number 5"),
      Malformed(
        name: "brace inside a group", text: c + "Group { numObjects 0 { } }",
        line: 2, column: 22, message: "unexpected '{' in Group"),

      // Numbers.
      Malformed(
        name: "number expected",
        text: c + "Group { numObjects 1 Sphere { center 0 zero 0 radius 1 } }",
        line: 2, column: 40, message: "expected a number, found 'zero'"),
      Malformed(
        name: "number cut short by a brace",
        text: c + "Group { numObjects 1 Sphere { center 0 0 } }",
        line: 2, column: 42, message: "expected a number, found '}'"),
      Malformed(
        name: "hexadecimal is not decimal",
        text: c + "Group { numObjects 1 Sphere { center 0x10 0 0 radius 1 } }",
        line: 2, column: 38, message: "expected a number, found '0x10'"),
      Malformed(
        name: "nan",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 radius nan } }",
        line: 2, column: 51, message: "expected a finite number, found 'nan'"),
      Malformed(
        name: "inf", text: "PerspectiveCamera { center -inf 0 0 }", line: 1,
        column: 28,
        message: "expected a finite number, found '-inf'"),
      Malformed(
        name: "overflowing literal",
        text: "PerspectiveCamera { center 0 0 0 angle 1e999 }", line: 1,
        column: 40,
        message:
          "'1e999' is beyond the finite range of double "
          + "(±1.7976931348623157e+308)"),
      Malformed(
        name: "zero radius",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 radius 0 } }",
        line: 2, column: 51, message: "'radius' must be positive, found 0"),
      Malformed(
        name: "negative radius",
        text: c + "Group { numObjects 1 Sphere { radius -2.5 center 0 0 0 } }",
        line: 2, column: 38, message: "'radius' must be positive, found -2.5"),
      Malformed(
        name: "zero plane normal",
        text: c + "Group { numObjects 1 Plane { normal 0 0 0 offset 1 } }",
        line: 2, column: 37, message: "'normal' must not be the zero vector"),
      Malformed(
        name: "zero light direction",
        text: c
          + "Lights { numLights 1 DirectionalLight { direction 0 0 0 color 1 "
          + "1 1 } }",
        line: 2, column: 51,
        message: "'direction' must not be the zero vector"),
      Malformed(
        name: "negative colour",
        text: c + "Background { color 0 -0.5 0 }", line: 2, column: 20,
        message: "'color' components must not be negative"),
      Malformed(
        name: "zero falloff",
        text: c
          + "Lights { numLights 1 PointLight { position 0 0 0 color 1 1 1 "
          + "falloff 0 } }",
        line: 2, column: 70, message: "'falloff' must be positive, found 0"),
      Malformed(
        name: "negative shininess",
        text: c
          + "Materials { numMaterials 1 Material { diffuseColor 1 1 1 "
          + "shininess -1 } }",
        line: 2, column: 68,
        message: "'shininess' must not be negative, found -1"),

      // The camera.
      Malformed(
        name: "camera angle 0",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 0 -1 up 0 1 0 angle 0 "
            + "}",
        line: 1, column: 66,
        message: "the camera's angle must be between 0 and 180 degrees, found 0"
      ),
      Malformed(
        name: "camera angle 180",
        text:
          "PerspectiveCamera {\n angle 180 center 0 0 0 direction 0 0 -1 up 0 "
            + "1 0 }",
        line: 2, column: 8,
        message:
          "the camera's angle must be between 0 and 180 degrees, found 180"),
      Malformed(
        name: "zero camera direction",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 0 0 up 0 1 0 angle 30 "
            + "}",
        line: 1, column: 44,
        message: "the camera's direction must not be zero"),
      Malformed(
        name: "up parallel to direction",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 1 0 up 0 -2 0 angle "
            + "30 }",
        line: 1, column: 53,
        message:
          "the camera's up vector must not be zero or parallel to its direction"
      ),
      Malformed(
        name: "zero up",
        text:
          "PerspectiveCamera { center 0 0 0 direction 0 1 0 up 0 0 0 angle 30 "
            + "}",
        line: 1, column: 53,
        message:
          "the camera's up vector must not be zero or parallel to its direction"
      ),

      // Material indices, checked once the materials are known.
      Malformed(
        name: "MaterialIndex out of range",
        text: c + "Materials { numMaterials 2 Material { diffuseColor 1 1 1 }\n"
          + "Material { diffuseColor 1 1 1 } }\nGroup { numObjects 1\n"
          + "  MaterialIndex 2 \(s) }",
        line: 5, column: 17,
        message:
          "MaterialIndex 2 is out of range: the scene has 2 materials (0 to "
            + "1)"),
      Malformed(
        name: "MaterialIndex out of range, materials after the group",
        text: c + "Group { numObjects 1 MaterialIndex 1 \(s) }\n"
          + "Materials { numMaterials 1 Material { diffuseColor 1 1 1 } }",
        line: 2, column: 36,
        message:
          "MaterialIndex 1 is out of range: the scene has 1 material (0 to 0)"),
      Malformed(
        name: "MaterialIndex out of range in a nested group, no materials",
        text: c
          + "Group { numObjects 1\n Group { numObjects 1\n  MaterialIndex 1 "
          + "\(s) } }",
        line: 4, column: 17,
        message: "MaterialIndex 1 is out of range: the scene has no materials "
          + "(only the default, 0)"),
      Malformed(
        name: "fractional MaterialIndex",
        text: c + "Group { numObjects 1 MaterialIndex 0.5 \(s) }", line: 2,
        column: 36,
        message: "'MaterialIndex' must be a whole number ≥ 0, found 0.5"),

      // Ends of file.
      Malformed(
        name: "unterminated group",
        text: c + "Group { numObjects 1\n  \(s)\n", line: 4, column: 1,
        message: "unexpected end of file: Group is missing its '}'"),
      Malformed(
        name: "unterminated sphere",
        text: c + "Group { numObjects 1 Sphere { center 0 0 0 radius 1",
        line: 2, column: 52,
        message: "unexpected end of file: Sphere is missing its '}'"),
      Malformed(
        name: "unterminated lights", text: c + "Lights { numLights 0 ", line: 2,
        column: 22,
        message: "unexpected end of file: Lights is missing its '}'"),
      Malformed(
        name: "end of file inside a vector",
        text: "PerspectiveCamera { center 0 0", line: 1, column: 31,
        message: "expected a number, found 'end of file'"),

      // Nesting: one level more than the limit, of groups alone or of
      // transforms inside a group, fails at the level past it.
    ]
      + [
        ("nesting beyond the maximum depth", "Group { numObjects 1\n"),
        (
          "transforms nested beyond the maximum depth",
          "Transform { Translate 0 0 0\n"
        ),
      ].map { name, level in
        let depth = SceneParser.maximumGroupDepth
        return Malformed(
          name: name,
          text: c + "Group { numObjects 1\n"
            + String(repeating: level, count: depth) + s
            + String(repeating: " }", count: depth + 1),
          line: depth + 2, column: 1,
          message: "Groups and Transforms are nested more than \(depth) deep")
      }
  }()
}
