import FastEngine
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// A lumpy closed mesh of a given triangle count on a ground plane, in the
/// course's text format with an OBJ file beside it: the shape of
/// `gen_mesh.py` from the course's tools (a sphere of latitude bands and
/// longitude segments, fans at the poles, two triangles per cell, displaced
/// along each vertex's direction by random bumps), drawn from SplitMix64 so
/// that the benchmark needs nothing outside the project.
package enum RandomMesh {
  /// Bands and segments with 2·segments·(bands − 1) = `count`, the bands as
  /// near the square root as a divisor allows; `count` is rounded up to an
  /// even number.
  static func grid(count: Int) -> (bands: Int, segments: Int) {
    let half = Swift.max(2, (count + 1) / 2)
    var rows = Swift.max(1, Int(Double(half / 2).squareRoot()))
    while half % rows != 0 { rows -= 1 }
    return (rows + 1, half / rows)
  }

  /// The OBJ file: v and f lines, 1-based, counter-clockwise from outside.
  package static func objText(count: Int, seed: UInt64 = 1) -> String {
    let (bands, segments) = grid(count: count)
    var generator = SplitMix64(seed: seed)
    // Bumps: a direction, a width in radians and a height.
    let bumps = (0..<48).map { index -> (Vector3<Double>, Double, Double) in
      let z = Double.random(in: -1...1, using: &generator)
      let phi = Double.random(in: 0..<(2 * .pi), using: &generator)
      let s = (1 - z * z).squareRoot()
      let width = 1.0 / (1 + Double(index) / 2)
      let height =
        Double.random(in: -0.12...0.12, using: &generator) * width.squareRoot()
      return (
        Vector3(s * Double.cos(phi), s * Double.sin(phi), z), width, height
      )
    }
    func vertex(_ direction: Vector3<Double>) -> Vector3<Double> {
      var radius = 1.0
      for (centre, width, height) in bumps {
        let cosine = direction.dot(centre)
        let angle = Double.acos(Swift.min(1, Swift.max(-1, cosine)))
        radius += height * Double.exp(-(angle * angle) / (width * width))
      }
      return Vector3(1.6 * direction.x, direction.y, direction.z) * radius
    }
    var lines: [String] = []
    func add(_ direction: Vector3<Double>) {
      let v = vertex(direction)
      lines.append(
        "v \(RandomSpheres.short(v.x)) \(RandomSpheres.short(v.y)) "
          + "\(RandomSpheres.short(v.z))")
    }
    add(Vector3(0, 1, 0))
    for band in 1..<bands {
      let theta = Double.pi * Double(band) / Double(bands)
      for segment in 0..<segments {
        let phi = 2 * Double.pi * Double(segment) / Double(segments)
        add(
          Vector3(
            Double.sin(theta) * Double.cos(phi), Double.cos(theta),
            Double.sin(theta) * Double.sin(phi)))
      }
    }
    add(Vector3(0, -1, 0))
    let bottom = 2 + (bands - 1) * segments
    func ring(_ band: Int, _ segment: Int) -> Int {
      2 + (band - 1) * segments + segment % segments
    }
    for segment in 0..<segments {
      lines.append("f 1 \(ring(1, segment + 1)) \(ring(1, segment))")
      lines.append(
        "f \(bottom) \(ring(bands - 1, segment)) "
          + "\(ring(bands - 1, segment + 1))")
    }
    for band in 1..<(bands - 1) {
      for segment in 0..<segments {
        let (a, b) = (ring(band, segment), ring(band, segment + 1))
        let (c, d) = (ring(band + 1, segment), ring(band + 1, segment + 1))
        lines.append("f \(a) \(b) \(d)")
        lines.append("f \(a) \(d) \(c)")
      }
    }
    return lines.joined(separator: "\n") + "\n"
  }

  /// The scene naming the OBJ file `objName` (beside it).
  package static func sceneText(objName: String) -> String {
    """
    PerspectiveCamera {
        center 3.6 3.2 7.6
        direction -0.3971313 -0.3420201 -0.8516507
        up 0 1 0
        angle 30
    }

    Lights {
        numLights 1
        DirectionalLight { direction -0.4 -1 -0.5  color 0.8 0.8 0.8 }
    }

    Background { color 0.1 0.12 0.18  ambientLight 0.2 0.2 0.2 }

    Materials {
        numMaterials 2
        PhongMaterial { diffuseColor 0.75 0.55 0.4  specularColor 0.3 0.3 0.3
                        shininess 20 }
        Material { diffuseColor 0.6 0.6 0.6 }
    }

    Group {
        numObjects 2
        MaterialIndex 0
        TriangleMesh { obj_file \(objName) }
        MaterialIndex 1
        Plane { normal 0 1 0  offset -1.3 }
    }

    """
  }
}
