// libFuzzer harness for the scene parser and the render of what it accepts.
// Built and run by Fuzz/run.sh, not by SwiftPM.
//
// Every input must either parse or throw one well-formed `SceneError`; a
// scene that parses must compile and render a 4x3 image with both kernels
// without trapping (the Float kernel only when the scene reads in float, as
// the command line requires, and with every sphere and triangle projected
// onto screen tiles; the Double one through the hierarchies). Anything else stops the fuzzer with the input
// saved.
//
// Checked always (invariants that hold by construction, so a failure is a
// bug):
// - the error is one line, `fuzz.txt:LINE:COLUMN: error: MESSAGE`, free of
//   control characters, with the position inside the input (or just past
//   its end);
// - a parsed scene has materials, every MaterialIndex in range, a finite
//   camera basis and, after its transforms, spheres with finite centres and
//   radii > 0, planes with unit normals, finite triangles and ellipsoids;
// - every depth is +inf (a miss) or finite and > 0, and a miss has a zero
//   normal;
// - a number the fast decimal parser accepts equals the standard library's
//   conversion of the same text, bit for bit.
// Checked with FUZZ_STRICT=1 only, and only for modest scenes, whose every
// number is 0 or of magnitude 1e-6 to 1e6 (scenes with radii near Double's
// limits, or values beyond Float's range in a Float render, are valid but
// render NaNs; see the report of the fuzzing run):
// - the normal of every hit is finite and unit length, the colour finite.

@testable import FastEngine
@testable import FastKernels
@testable import SceneIO
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import PlatformSupport

/// Extra render checks, off by default: see the file header.
let strictChecks =
  getenv("FUZZ_STRICT").map { $0.pointee == UInt8(ascii: "1") } ?? false

@_cdecl("LLVMFuzzerTestOneInput")
public func fuzzSceneParser(_ data: UnsafePointer<UInt8>?, _ size: Int) -> CInt
{
  let bytes =
    data.map { Array(UnsafeBufferPointer(start: $0, count: size)) } ?? []
  checkNumbers(bytes)
  // The bytes entry rather than `parse(_:file:)`: a String would have
  // replaced invalid UTF-8 before the tokenizer saw it, and a file read
  // from disk reaches the tokenizer as raw bytes too.
  let scene: Scene
  do throws(SceneError) {
    scene = try SceneParser.parse(bytes: bytes, file: "fuzz.txt")
  } catch {
    checkError(error, bytes)
    return 0
  }
  checkScene(scene)
  let strict = strictChecks && isModest(scene)
  render(
    scene, StableKernel<Double>.self, style: .course, hierarchyThreshold: 1,
    strict: strict)
  // In float only what the command line renders in float: the scene read
  // again for that precision (numbers beyond it are errors at their
  // position, checked as every error is) and not refused for a sphere too
  // small beside the rest at any common scale.
  let floatScene: Scene
  do throws(SceneError) {
    floatScene = try SceneParser.parse(
      bytes: bytes, file: "fuzz.txt",
      options: SceneOptions(style: .course, precision: .float))
  } catch {
    checkError(error, bytes)
    return 0
  }
  guard LengthScale.problem(floatScene, precision: .float) == nil else {
    return 0
  }
  render(
    floatScene, NaiveKernel<Float>.self, style: .mit,
    hierarchyThreshold: nil, projected: true, strict: strict)
  return 0
}

/// Stops the fuzzer: libFuzzer saves the input as a crash.
func fail(_ message: String) -> Never {
  fatalError("fuzz invariant: \(message)")
}

// MARK: - Errors

func checkError(_ error: SceneError, _ bytes: [UInt8]) {
  let description = Array(error.description.utf8)
  // One line, and nothing else a terminal would act on: no C0 or C1
  // control, DEL, or Unicode line or paragraph separator.
  let controls = error.description.unicodeScalars.filter {
    $0.value < 0x20 || (0x7F...0x9F).contains($0.value) || $0.value == 0x2028
      || $0.value == 0x2029
  }
  guard controls.isEmpty else {
    fail(
      "the error holds control characters: \(error.description.debugDescription)"
    )
  }
  let prefix = Array("fuzz.txt:\(error.line):\(error.column): error: ".utf8)
  guard error.file == "fuzz.txt", description.starts(with: prefix),
    description.count > prefix.count
  else {
    fail(
      "the error is not FILE:LINE:COLUMN: error: MESSAGE: \(error.description)")
  }
  // Lines and their lengths, as the tokenizer counts them.
  var lineLengths = [0]
  for byte in bytes {
    if byte == UInt8(ascii: "\n") {
      lineLengths.append(0)
    } else {
      lineLengths[lineLengths.count - 1] += 1
    }
  }
  guard error.line >= 1, error.line <= lineLengths.count,
    error.column >= 1, error.column <= lineLengths[error.line - 1] + 1
  else {
    fail(
      "position \(error.line):\(error.column) is outside the input "
        + "(\(lineLengths.count) lines): \(error.description)")
  }
}

// MARK: - Numbers

/// The fast path of `DecimalParser` must agree with the standard library on
/// every word it accepts; words it refuses are the parser's business.
func checkNumbers(_ bytes: [UInt8]) {
  var tokenizer = SceneTokenizer(bytes: bytes)
  // A bound on the work per input, however many tokens it holds.
  for _ in 0..<256 {
    let token = tokenizer.next()
    if token.kind == .end { return }
    guard token.kind == .word, let value = tokenizer.number(token) else {
      continue
    }
    let text = tokenizer.text(of: token)
    guard let reference = Double(text) else {
      fail("DecimalParser accepts '\(text)', the standard library does not")
    }
    guard
      value.bitPattern == reference.bitPattern
        || (value.isNaN && reference.isNaN)
    else {
      fail(
        "DecimalParser reads '\(text)' as \(value), the standard library as \(reference)"
      )
    }
  }
}

// MARK: - Scenes

func checkScene(_ scene: Scene) {
  guard !scene.materials.isEmpty else { fail("a scene without materials") }
  let camera = scene.camera
  guard camera.center.isFinite, camera.direction.isFinite,
    camera.horizontal.isFinite, camera.up.isFinite,
    camera.focalDistance.isFinite, camera.focalDistance > 0
  else {
    fail("a camera without a finite basis: \(camera)")
  }
  // Transforms applied: the parser refuses what they take beyond Double.
  let primitives = scene.root.flattened()
  for sphere in primitives.spheres {
    guard sphere.center.isFinite, sphere.radius.isFinite, sphere.radius > 0
    else { fail("a sphere that should not have parsed: \(sphere)") }
    guard scene.materials.indices.contains(sphere.materialIndex) else {
      fail(
        "sphere material \(sphere.materialIndex) of \(scene.materials.count)")
    }
  }
  for plane in primitives.planes {
    guard plane.normal.isFinite, plane.offset.isFinite,
      (plane.normal.length - 1).magnitude < 1e-12
    else { fail("a plane that should not have parsed: \(plane)") }
    guard scene.materials.indices.contains(plane.materialIndex) else {
      fail("plane material \(plane.materialIndex) of \(scene.materials.count)")
    }
  }
  for triangle in primitives.triangles {
    guard triangle.v0.isFinite, triangle.v1.isFinite, triangle.v2.isFinite
    else {
      fail("a triangle that should not have parsed: \(triangle)")
    }
    guard scene.materials.indices.contains(triangle.materialIndex) else {
      fail(
        "triangle material \(triangle.materialIndex) of \(scene.materials.count)"
      )
    }
  }
  for ellipsoid in primitives.transformedSpheres {
    guard ellipsoid.matrix.rowMajorEntries.allSatisfy(\.isFinite),
      ellipsoid.inverse.rowMajorEntries.allSatisfy(\.isFinite)
    else { fail("an ellipsoid that should not have parsed: \(ellipsoid)") }
    guard scene.materials.indices.contains(ellipsoid.sphere.materialIndex)
    else {
      fail(
        "ellipsoid material \(ellipsoid.sphere.materialIndex) of "
          + "\(scene.materials.count)")
    }
  }
  for light in scene.lights {
    switch light {
    case .point(let position, let color, let falloff):
      guard position.isFinite, color.isFinite, falloff.map({ $0 > 0 }) ?? true
      else { fail("a light that should not have parsed: \(light)") }
    case .directional(let direction, let color):
      guard direction.isFinite, color.isFinite else {
        fail("a light that should not have parsed: \(light)")
      }
    }
  }
}

/// Whether every number of the scene is 0 or of magnitude 1e-6 to 1e6.
func isModest(_ scene: Scene) -> Bool {
  var values: [Double] = []
  func add(_ vector: Vector3<Double>) {
    values += [vector.x, vector.y, vector.z]
  }
  add(scene.camera.center)
  values.append(scene.camera.angle)
  add(scene.background)
  add(scene.ambient)
  for material in scene.materials {
    add(material.diffuse)
    add(material.specular)
    values.append(material.shininess)
  }
  for light in scene.lights {
    switch light {
    case .point(let position, let color, let falloff):
      add(position)
      add(color)
      values.append(falloff ?? 1)
    case .directional(_, let color):
      add(color)
    }
  }
  let primitives = scene.root.flattened()
  for sphere in primitives.spheres {
    add(sphere.center)
    values.append(sphere.radius)
  }
  for plane in primitives.planes {
    add(plane.normal * plane.offset)
  }
  for triangle in primitives.triangles {
    add(triangle.v0)
    add(triangle.v1)
    add(triangle.v2)
  }
  for ellipsoid in primitives.transformedSpheres {
    values += ellipsoid.matrix.rowMajorEntries
  }
  return values.allSatisfy { $0 == 0 || (1e-6...1e6).contains($0.magnitude) }
}

func render<Kernel: IntersectionKernel>(
  _ scene: Scene, _ kernel: Kernel.Type, style: ImageStyle,
  hierarchyThreshold: Int?, projected: Bool = false, strict: Bool
) {
  // Projected: every sphere and triangle through screen tiles, as large
  // scenes are rendered (the tiles decline, and hierarchies are built,
  // where they overlap too much).
  let compiled =
    projected
    ? CompiledScene<Kernel>(
      scene, projectionThreshold: 0, triangleProjectionThreshold: 0)
    : hierarchyThreshold.map {
      CompiledScene<Kernel>(scene, hierarchyThreshold: $0)
    }
    ?? CompiledScene<Kernel>(scene)
  let settings = RenderSettings(
    width: 4, height: 3, outputs: [.depth, .normals, .shaded], style: style,
    threads: 1)
  let buffers = Renderer.render(compiled, settings: settings)
  let pixels = settings.width * settings.height
  guard buffers.depth.count == pixels, buffers.normals.count == pixels,
    buffers.color.count == pixels
  else { fail("buffers of the wrong size") }
  for pixel in 0..<pixels {
    let t = buffers.depth[pixel]
    let normal = buffers.normals[pixel]
    guard t == .infinity || (t.isFinite && t > 0) else {
      fail("\(Kernel.self) pixel \(pixel): depth \(t)")
    }
    if t == .infinity {
      guard normal == .zero else {
        fail("\(Kernel.self) pixel \(pixel): a miss with normal \(normal)")
      }
    } else if strict {
      guard normal.isFinite, (normal.length - 1).magnitude < 1e-3 else {
        fail("\(Kernel.self) pixel \(pixel): t \(t), normal \(normal)")
      }
    }
    if strict {
      guard buffers.color[pixel].isFinite else {
        fail("\(Kernel.self) pixel \(pixel): colour \(buffers.color[pixel])")
      }
    }
  }
}
