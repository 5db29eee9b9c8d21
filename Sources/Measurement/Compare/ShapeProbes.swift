import Geometry
import SceneDescription

/// The course's shapes a scene uses, as the probes know them.
package enum ProbedKind: String, CaseIterable, Sendable {
  case sphere = "Sphere"
  case plane = "Plane"
  case triangle = "Triangle"
  case transform = "Transform"

  var probes: [ShapeProbe] {
    switch self {
    case .sphere: ShapeProbe.sphere
    case .plane: ShapeProbe.plane
    case .triangle: ShapeProbe.triangle
    case .transform: ShapeProbe.transform
    }
  }
}

/// What the probes found: for each shape asked, how many probes it
/// failed, one line per cause, and what was checked of shapes of one's
/// own.
package struct ShapeProbeReport: Sendable {
  package struct Probed: Sendable {
    package var name: String
    package var probes: Int
    package var failed: Int
  }

  package var probed: [Probed] = []
  /// The first failing probe of each cause, shape by shape; then the
  /// first failing ray of each type of shape of one's own.
  package var diagnoses: [ShapeDiagnosis] = []
  /// Shapes not probed, and what was checked of shapes of one's own.
  package var notes: [String] = []

  package var passes: Bool {
    diagnoses.isEmpty && probed.allSatisfy { $0.failed == 0 }
  }

  /// What `--check` prints before rendering; nothing when the scene has
  /// no shape to ask. When a probe fails, the last line says that the
  /// images were not compared.
  package var lines: [String] {
    guard !probed.isEmpty || !notes.isEmpty else { return [] }
    var lines: [String] = []
    if !probed.isEmpty {
      let counts = probed.map {
        $0.failed == 0
          ? "\($0.name) passed \($0.probes)"
          : "\($0.name) failed \($0.failed) of \($0.probes)"
      }
      lines.append(
        "shape probes (rays whose answers are known, before rendering): "
          + counts.joined(separator: ", "))
    }
    // A shape of one's own has its failure among the notes, under its
    // note.
    lines += diagnoses.filter { !$0.isOwnShape }.map { "  " + $0.line }
    lines += notes
    if !passes {
      lines.append(
        "the images were not compared: fix the shape first (a shape that "
          + "fails a probe draws wrong, and the probe says why)")
    }
    return lines
  }
}

/// `raytrace SCENE --check`'s first step: the course's shapes the scene
/// uses, asked with rays of the check's own whose answers are known in
/// closed form (`ShapeProbe`), each failure named with its likely cause;
/// and each shape of one's own (docs/ADDING-A-SHAPE.md), which the probes
/// do not know, checked for what any `Hittable` must do.
package enum ShapeProbes {
  /// The probes of the kinds `scene` uses (a transform's are asked over a
  /// sphere, whose probes it needs), and its shapes of one's own checked.
  package static func check(
    _ scene: Scene, factories: ShapeFactories = .course
  ) -> ShapeProbeReport {
    var kinds = Set<ProbedKind>()
    var own: [Shape] = []
    var seen = Set<Shape>()
    collect(scene.root.objects, into: &kinds, own: &own, seen: &seen)
    return probe(kinds, own: own, factories: factories)
  }

  /// The probes of `kinds`, in the order of `ProbedKind`, and the shapes
  /// `own` checked.
  package static func probe(
    _ kinds: Set<ProbedKind>, own: [Shape] = [],
    factories: ShapeFactories = .course
  ) -> ShapeProbeReport {
    var report = ShapeProbeReport()
    var asked = kinds
    if kinds.contains(.transform) { asked.insert(.sphere) }
    for kind in ProbedKind.allCases where asked.contains(kind) {
      let sphereFails = report.probed.contains {
        $0.name == ProbedKind.sphere.rawValue && $0.failed > 0
      }
      if kind == .transform, sphereFails {
        report.notes.append(
          "Transform: not probed, since the Sphere it is probed over "
            + "fails its own probes")
        continue
      }
      let (failed, diagnoses) = run(kind.probes, factories: factories)
      report.probed.append(
        .init(name: kind.rawValue, probes: kind.probes.count, failed: failed))
      report.diagnoses += diagnoses
    }
    checkOwn(own, into: &report)
    return report
  }

  /// Every probe asked; a failing one names its cause unless a probe it
  /// is controlled by failed (that one's cause comes first) or its cause
  /// was named already.
  static func run(_ probes: [ShapeProbe], factories: ShapeFactories)
    -> (failed: Int, diagnoses: [ShapeDiagnosis])
  {
    var failedIDs = Set<String>()
    var causes = Set<ProbeCause>()
    var diagnoses: [ShapeDiagnosis] = []
    for probe in probes {
      let diagnosis: ShapeDiagnosis?
      if let object = probe.make(factories) {
        let got = object.intersect(
          probe.ray, after: probe.tMin, before: probe.tMax)
        diagnosis = probe.judge(got)
      } else {
        diagnosis = ShapeDiagnosis(
          shape: probe.texts.name, probe: probe.id, cause: .formula,
          line: "\(probe.texts.name), \(probe.what): could not be made "
            + "(an invertible matrix refused?)")
      }
      guard let diagnosis else { continue }
      failedIDs.insert(probe.id)
      if probe.controls.contains(where: failedIDs.contains) { continue }
      if causes.insert(diagnosis.cause).inserted {
        diagnoses.append(diagnosis)
      }
    }
    return (failedIDs.count, diagnoses)
  }

  /// The kinds of the course's shapes under `objects` (a mesh's are
  /// triangles), and the shapes of one's own, each once.
  static func collect(
    _ objects: [SceneObject<Double>], into kinds: inout Set<ProbedKind>,
    own: inout [Shape], seen: inout Set<Shape>
  ) {
    for object in objects {
      switch object {
      case .sphere: kinds.insert(.sphere)
      case .plane: kinds.insert(.plane)
      case .triangle, .mesh: kinds.insert(.triangle)
      case .group(let group):
        collect(group.objects, into: &kinds, own: &own, seen: &seen)
      case .transform(let transform):
        kinds.insert(.transform)
        collect(
          [transform.object], into: &kinds, own: &own, seen: &seen)
      case .shape(let shape):
        if seen.insert(shape).inserted { own.append(shape) }
      }
    }
  }
}
