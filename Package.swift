// swift-tools-version:6.0
import PackageDescription

// Two targets stand in for packages this machine cannot fetch; each copies the
// real package's names, so adopting the package means deleting its folder and
// replacing the target below with a package dependency:
//   RealModule      -> swift-numerics (product "RealModule")
//   ArgumentParser  -> swift-argument-parser (product "ArgumentParser")
let package = Package(
  name: "raytrace",
  products: [
    .executable(name: "raytrace", targets: ["raytrace"]),
    .library(name: "RayTracer", targets: ["RayTracer"]),
  ],
  targets: [
    // The system zlib (zlib1g-dev on Debian, part of the SDK on macOS).
    .systemLibrary(
      name: "CZlib",
      providers: [.apt(["zlib1g-dev"]), .brew(["zlib"])]
    ),
    .target(name: "RealModule"),
    .target(name: "ArgumentParser"),
    .target(
      name: "RayTracer",
      dependencies: ["RealModule", "CZlib"]
    ),
    .executableTarget(
      name: "raytrace",
      dependencies: ["RayTracer", "ArgumentParser"]
    ),
    .testTarget(
      name: "RayTracerTests",
      dependencies: ["RayTracer", "raytrace"]
    ),
    .testTarget(
      name: "ArgumentParserTests",
      dependencies: ["ArgumentParser"]
    ),
  ]
)
