import ArgumentParser
import RayTracer

@main
struct Raytrace: ParsableCommand {
  static let configuration = CommandConfiguration(
    commandName: "raytrace",
    abstract:
      "Ray-cast a scene of spheres and planes into shaded, depth and normal images.",
    subcommands: [Render.self, Report.self, Bench.self],
    defaultSubcommand: Render.self)
}

extension ImageStyle: ExpressibleByArgument {}
extension Precision: ExpressibleByArgument {}
extension IntersectionMethod: ExpressibleByArgument {}
extension PixelFilter: ExpressibleByArgument {}
extension Engine: ExpressibleByArgument {}
extension ReferencePrecision: ExpressibleByArgument {}
