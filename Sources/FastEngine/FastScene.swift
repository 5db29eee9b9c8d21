import FastKernels
import ExactArithmetic
import Geometry
import SceneDescription
import PlatformSupport

/// The fast engine behind one type that is not generic: a scene compiled
/// for the options' precision and method, and its renders. The targets
/// above hold this, so that every generic
/// function of the engine is specialised here, in its own module, for the
/// four kernels: called from another module, a generic function of this
/// one runs unspecialised (a render 100 times slower).
package struct FastScene: Sendable {
  /// The scene's primitives, as compiled.
  package let spheres: Int
  package let planes: Int
  package let triangles: Int
  package let ellipsoids: Int
  private let draw:
    @Sendable (
      RenderSettings, (@Sendable (Int) -> Void)?, consuming AnyRenderBuffers?
    ) -> FastRender

  /// Compiles `scene` with the kernel of `options`.
  ///
  /// - Parameter thresholds: `.render` for the thresholds a render uses
  ///   (`FastOptions`' or the measured defaults, `supersampled` widening
  ///   the projection's), `.compiled` for `CompiledScene`'s own defaults
  ///   (what the report and the tests measure).
  /// - Parameter threads: the render's, for building hierarchies (the same
  ///   for any count).
  package init(
    _ scene: Scene, textures: [Texture?] = [], options: FastOptions,
    thresholds: Thresholds = .compiled,
    threads: Int = Platform.availableCores
  ) {
    self = options.withKernel(
      Compile(
        scene: scene, textures: textures, options: options,
        thresholds: thresholds, threads: threads))
  }

  /// Where the compiled scene's search thresholds come from.
  package enum Thresholds: Sendable {
    /// A render's: no hierarchy of spheres unless projection declines;
    /// the projection thresholds measured for one sample or several.
    case render(supersampled: Bool)
    /// `CompiledScene`'s defaults.
    case compiled
  }

  /// Renders the outputs `settings` asks for, reusing `recycling`'s
  /// arrays where they fit (a repeated render). The scene's search is
  /// kept for the next render (`SearchCache`): its hierarchies, and the
  /// screen tiles of the last view, while this value lives.
  package func render(
    _ settings: RenderSettings, progress: (@Sendable (Int) -> Void)? = nil,
    recycling: consuming AnyRenderBuffers? = nil
  ) -> FastRender {
    draw(settings, progress, consume recycling)
  }

  private init<Kernel: IntersectionKernel>(_ compiled: CompiledScene<Kernel>) {
    spheres = compiled.sphereCount
    planes = compiled.planeCount
    triangles = compiled.triangleCount
    ellipsoids = compiled.ellipsoidCount
    let cache = SearchCache<Kernel>()
    draw = { settings, progress, recycling in
      // Taken out of the enum, not copied: the renderer reuses arrays
      // only where nothing else holds them.
      let recycled = AnyRenderBuffers.take(
        consume recycling, as: Kernel.Scalar.self)
      let result = Renderer.renderReportingSearch(
        compiled, settings: settings, cache: cache, progress: progress,
        recycling: consume recycled)
      return FastRender(
        buffers: AnyRenderBuffers(result.buffers), search: result.search,
        triangleSearch: result.triangleSearch)
    }
  }

  /// The compile for the kernel `FastOptions.withKernel` chose.
  private struct Compile: KernelBody {
    var scene: Scene
    var textures: [Texture?]
    var options: FastOptions
    var thresholds: Thresholds
    var threads: Int

    func run<Kernel: IntersectionKernel>(_: Kernel.Type) -> FastScene {
      switch thresholds {
      case .compiled:
        return FastScene(
          CompiledScene<Kernel>(
            scene, textures: textures, threads: threads))
      case .render(let supersampled):
        // Spheres are culled per tile below the projection threshold and
        // projected above it, a hierarchy built only where the projection
        // declines (`Renderer.renderReportingSearch`); supersampled renders
        // too, their tiles and boxes widened by the filter's reach.
        return FastScene(
          CompiledScene<Kernel>(
            scene, textures: textures,
            hierarchyThreshold: options.hierarchyThreshold ?? .max,
            projectionThreshold: options.projectionThreshold
              ?? (supersampled
                ? CompiledScene<Kernel>.supersampledProjectionThreshold
                : CompiledScene<Kernel>.projectionThreshold),
            triangleProjectionThreshold: options.triangleProjectionThreshold
              ?? CompiledScene<Kernel>.triangleProjectionThreshold,
            threads: threads))
      }
    }
  }
}

/// A fast render's buffers and how it searched.
package struct FastRender: Sendable {
  package var buffers: AnyRenderBuffers
  package var search: Renderer.SphereSearch
  package var triangleSearch: Renderer.TriangleSearch
}

/// The buffers of a Float or a Double render.
package enum AnyRenderBuffers: Sendable {
  case float(RenderBuffers<Float>)
  case double(RenderBuffers<Double>)

  /// No dynamic cast: the type test folds away once S is known, and a
  /// cast of a generic struct asks the runtime (measured: a scan of the
  /// conformances inside the timed render).
  @inline(__always)
  package init<S: RayScalar>(_ buffers: consuming RenderBuffers<S>) {
    if S.self == Float.self {
      self = .float(unsafeBitCast(buffers, to: RenderBuffers<Float>.self))
    } else if S.self == Double.self {
      self = .double(unsafeBitCast(buffers, to: RenderBuffers<Double>.self))
    } else {
      preconditionFailure("the fast engine renders in Float or Double")
    }
  }

  /// The buffers of `any`, if they are of precision S, moved out of it.
  @inline(__always)
  static func take<S: RayScalar>(
    _ any: consuming AnyRenderBuffers?, as _: S.Type
  ) -> RenderBuffers<S>? {
    switch consume any {
    case .float(let buffers)? where S.self == Float.self:
      unsafeBitCast(buffers, to: RenderBuffers<S>.self)
    case .double(let buffers)? where S.self == Double.self:
      unsafeBitCast(buffers, to: RenderBuffers<S>.self)
    default: nil
    }
  }

  /// Every value widened to Double (exactly).
  package var doubles: RenderBuffers<Double> {
    switch self {
    case .double(let buffers): return buffers
    case .float(let buffers):
      var wide = RenderBuffers<Double>(
        width: buffers.width, height: buffers.height,
        depth: buffers.depth.map(Double.init),
        normals: buffers.normals.map(Vector3<Double>.init),
        color: buffers.color.map(Vector3<Double>.init))
      wide.normalBytes = buffers.normalBytes
      wide.colorBytes = buffers.colorBytes
      return wide
    }
  }
}

extension FastScene {
  /// The engine in a wider scalar: the very camera rays a render in
  /// `precision` traces, intersected by the stable method in R
  /// (ReferenceScalar, or DoubleDouble), with `CompiledScene`'s own
  /// thresholds: what a render's error is measured against. Specialised
  /// here, in the engine's module, for every R a caller asks.
  package static func reference<R: RayScalar>(
    _ scene: Scene, settings: RenderSettings, rays precision: Precision,
    in _: R.Type
  ) -> RenderBuffers<R> {
    #if (arch(i386) || arch(x86_64)) && !os(Windows) && !os(Android)
      if R.self == Float80.self {
        return referenceRender(scene, settings, precision, Float80.self)
          as! RenderBuffers<R>
      }
    #endif
    if R.self == DoubleDouble.self {
      return referenceRender(scene, settings, precision, DoubleDouble.self)
        as! RenderBuffers<R>
    }
    return referenceRender(scene, settings, precision, R.self)
  }

  private static func referenceRender<R: RayScalar>(
    _ scene: Scene, _ settings: RenderSettings, _ precision: Precision,
    _: R.Type
  ) -> RenderBuffers<R> {
    let compiled = CompiledScene<StableKernel<R>>(scene)
    switch precision {
    case .float:
      return Renderer.render(compiled, settings: settings, rays: Float.self)
    case .double:
      return Renderer.render(compiled, settings: settings, rays: Double.self)
    }
  }
}
