import FastKernels
extension CompiledScene {
  /// Whether every primitive the scene holds is of one of `kinds`: what a
  /// fast path for some kinds asks, so that a kind added later is not
  /// taken for absent.
  func holdsOnly(_ kinds: [PrimitiveKind]) -> Bool {
    PrimitiveKind.allCases.allSatisfy { kind in
      if kinds.contains(kind) { return true }
      switch kind {
      case .sphere: return spheres.isEmpty
      case .plane: return planes.isEmpty
      case .triangle: return triangles.isEmpty
      case .ellipsoid: return ellipsoids.isEmpty
      case .shape: return shapes.isEmpty
      }
    }
  }
}
