import FastKernels

/// How the fast engine renders: its precision and method, and the scene
/// sizes from which it changes its search.
package struct FastOptions: Sendable {
  package var precision: Precision
  package var method: IntersectionMethod
  /// Spheres from which a BVH is built (never when nil).
  package var hierarchyThreshold: Int?
  /// Spheres from which a render projects them onto screen tiles instead
  /// (`CompiledScene.projectionThreshold` when nil).
  package var projectionThreshold: Int?
  /// Triangles from which a render projects them onto screen tiles instead
  /// of building a hierarchy (`CompiledScene.triangleProjectionThreshold`
  /// when nil).
  package var triangleProjectionThreshold: Int?

  package init(
    precision: Precision = .double, method: IntersectionMethod = .stable
  ) {
    self.precision = precision
    self.method = method
  }

  /// `body`'s answer for the kernel of this precision and method: the one
  /// place that turns the two choices into a type.
  func withKernel<Body: KernelBody>(_ body: Body)
    -> Body.Result
  {
    switch (precision, method) {
    case (.float, .naive): return body.run(NaiveKernel<Float>.self)
    case (.float, .stable): return body.run(StableKernel<Float>.self)
    case (.double, .naive): return body.run(NaiveKernel<Double>.self)
    case (.double, .stable): return body.run(StableKernel<Double>.self)
    }
  }
}

/// Work generic over the fast engine's kernel (`FastOptions.withKernel`).
protocol KernelBody {
  associatedtype Result
  func run<Kernel: IntersectionKernel>(_ kernel: Kernel.Type) -> Result
}
