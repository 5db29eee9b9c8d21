// swift-tools-version:6.0
import PackageDescription

// Two targets stand in for packages this machine cannot fetch; each copies the
// real package's names, so adopting the package means deleting its folder and
// replacing the target below with a package dependency:
//   RealModule      -> swift-numerics (product "RealModule")
//   ArgumentParser  -> swift-argument-parser (product "ArgumentParser")
// `swift run` and `swift test` build for debugging. The renderer's library
// is optimised in those builds too, with its assertions kept
// (`-assert-config Debug`), so that the course's `swift run raytrace …`
// renders at nearly the speed of a release build. To step through the
// library in a debugger without optimisation:
//   RAYTRACE_UNOPTIMIZED=1 swift build
let optimizedInDebugBuilds: [SwiftSetting] =
  Context.environment["RAYTRACE_UNOPTIMIZED"] != nil
  ? []
  : [
    .unsafeFlags(
      [
        "-O", "-whole-module-optimization", "-num-threads", "2",
        "-assert-config", "Debug",
      ],
      .when(configuration: .debug))
  ]

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
      dependencies: ["RealModule", "CZlib"],
      swiftSettings: optimizedInDebugBuilds
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
