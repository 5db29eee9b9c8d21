import FastEngine
import SceneIO
import Geometry
import SceneDescription
import PlatformSupport

/// Scenes of many random spheres in the course's text format, laid out as
/// the course tools' `gen_spheres.py` lays them out (centres uniform in
/// [−10, 10]³, radii uniform in [r/2, r] with r = 1.6·10/√n, so about half
/// the camera rays hit whatever the count; four materials; the camera on +z
/// framing the cube's near face), but drawn from SplitMix64 so that the
/// benchmark needs nothing outside the project.
package enum RandomSpheres {
  package static func sceneText(count: Int, seed: UInt64 = 1) -> String {
    precondition(count > 0)
    let box = 10.0
    let angle = 30.0
    let distance = 1.05 * box / Double.tan(angle * .pi / 360)
    let largest = 1.6 * box / Double(count).squareRoot()
    var generator = SplitMix64(seed: seed)
    var groups = [[String]](repeating: [], count: 4)
    for _ in 0..<count {
      let x = Double.random(in: -box...box, using: &generator)
      let y = Double.random(in: -box...box, using: &generator)
      let z = Double.random(in: -box...box, using: &generator)
      let radius = Double.random(in: (largest / 2)...largest, using: &generator)
      let material = Int.random(in: 0..<4, using: &generator)
      groups[material].append(
        "    Sphere { center \(short(x)) \(short(y)) \(short(z))  "
          + "radius \(short(radius)) }"
      )
    }
    var text = """
      PerspectiveCamera {
          center 0 0 \(short(box + distance))
          direction 0 0 -1
          up 0 1 0
          angle \(Int(angle))
      }

      Lights {
          numLights 2
          DirectionalLight { direction -0.5 -1 -0.7  color 0.7 0.7 0.7 }
          PointLight { position 10 10 30  color 0.5 0.5 0.5
                       falloff \(short(1 / (11 * box * box))) }
      }

      Background { color 0 0 0  ambientLight 0.2 0.2 0.2 }

      Materials {
          numMaterials 4
          Material { diffuseColor 0.8 0.2 0.2  specularColor 0.5 0.5 0.5
                     shininess 20 }
          Material { diffuseColor 0.2 0.7 0.2 }
          Material { diffuseColor 0.2 0.3 0.9  specularColor 0.8 0.8 0.8
                     shininess 64 }
          Material { diffuseColor 0.9 0.8 0.3  specularColor 0.3 0.3 0.3
                     shininess 8 }
      }

      Group {
          numObjects \(count)

      """
    for (material, lines) in groups.enumerated() where !lines.isEmpty {
      text += "    MaterialIndex \(material)\n"
      text += lines.joined(separator: "\n") + "\n"
    }
    return text + "}\n"
  }

  /// Seven significant digits, as the Python generator writes them: enough
  /// for the scene, and a third of the file size of Double's shortest form.
  static func short(_ value: Double) -> String {
    let rounded = Float(value)
    var text = "\(rounded)"
    if text.hasSuffix(".0") { text.removeLast(2) }
    return text
  }
}
