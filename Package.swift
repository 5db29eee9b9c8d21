// swift-tools-version:6.0
import Foundation
import PackageDescription

// Two packages, in one of two forms (docs/PORTABILITY.md, "Packages"):
//
// - By default, two targets stand in for them, built with no network:
//   Sources/ArgumentParser copies the names of swift-argument-parser's
//   product ArgumentParser, Sources/RealModule those of swift-numerics'
//   product RealModule (Tests/ArgumentParserTests tests the stand-in).
// - With RAYTRACE_PACKAGES set, the real packages instead, and the stand-ins
//   are not declared at all:
//     RAYTRACE_PACKAGES=apple          from GitHub (needs the network)
//     RAYTRACE_PACKAGES=PARSER:NUMERICS  local checkouts of each
//   RAYTRACE_ARGUMENT_PARSER_PATH and RAYTRACE_NUMERICS_PATH name one local
//   checkout each (and choose the real packages on their own too).
// Fuzz/run.sh reads the same variables.
let environment = ProcessInfo.processInfo.environment

func variable(_ name: String) -> String? {
  guard let value = environment[name], !value.isEmpty else { return nil }
  return value
}

/// Where each real package comes from: a local path, or nil for GitHub.
struct RealPackages {
  var argumentParserPath: String?
  var numericsPath: String?
}

let realPackages: RealPackages? = {
  let parserPath = variable("RAYTRACE_ARGUMENT_PARSER_PATH")
  let numericsPath = variable("RAYTRACE_NUMERICS_PATH")
  switch variable("RAYTRACE_PACKAGES") {
  case nil where parserPath == nil && numericsPath == nil:
    return nil
  case nil, "apple"?:
    return RealPackages(
      argumentParserPath: parserPath, numericsPath: numericsPath)
  case let value? where value.contains(":"):
    let paths = value.split(separator: ":", maxSplits: 1).map(String.init)
    guard paths.count == 2, !paths[0].isEmpty, !paths[1].isEmpty else {
      fatalError(
        "RAYTRACE_PACKAGES='\(value)': expected "
          + "PARSER_CHECKOUT:NUMERICS_CHECKOUT")
    }
    return RealPackages(
      argumentParserPath: parserPath ?? paths[0],
      numericsPath: numericsPath ?? paths[1])
  case let value?:
    fatalError(
      "RAYTRACE_PACKAGES='\(value)': expected 'apple' or "
        + "PARSER_CHECKOUT:NUMERICS_CHECKOUT")
  }
}()

/// A package from a local checkout, or from its URL at `version` or later;
/// returns the dependency and the package's identity for `.product`.
func dependency(path: String?, url: String, from version: Version)
  -> (Package.Dependency, String)
{
  guard let path else {
    let name = URL(string: url)?.deletingPathExtension().lastPathComponent
    return (.package(url: url, from: version), name ?? url)
  }
  // SwiftPM names a local package after its folder.
  let name = URL(fileURLWithPath: path).standardizedFileURL.lastPathComponent
  return (.package(path: path), name)
}

var dependencies: [Package.Dependency] = []
var argumentParser: Target.Dependency = "ArgumentParser"
var realModule: Target.Dependency = "RealModule"
var standIns: [Target] = [
  .target(name: "RealModule"),
  .target(name: "ArgumentParser"),
  .testTarget(
    name: "ArgumentParserTests",
    dependencies: ["ArgumentParser"]
  ),
]

if let realPackages {
  let (parser, parserName) = dependency(
    path: realPackages.argumentParserPath,
    url: "https://github.com/apple/swift-argument-parser.git",
    from: "1.5.0")
  let (numerics, numericsName) = dependency(
    path: realPackages.numericsPath,
    url: "https://github.com/apple/swift-numerics.git",
    from: "1.0.0")
  dependencies = [parser, numerics]
  argumentParser = .product(name: "ArgumentParser", package: parserName)
  realModule = .product(name: "RealModule", package: numericsName)
  standIns = []
}

// `swift run` and `swift test` build for debugging. The course target is
// built without optimisation there, so that a debugger stopped in
// `Sphere.intersect` shows its variables (docs/PORTABILITY.md,
// "Debugging"). The geometry leaf below it is optimised in those builds
// (it is small: a few seconds, and a student does not edit it), with the
// vector operations the course calls prespecialised for Double
// (`@_specialize`), so that the course engine still renders every course
// scene at 800×800 within 2 s. The fast engine is optimised in those
// builds too: unoptimised, its generic kernels spent most of `swift test`
// looking up generic metadata (62 s of test time, 53.5 s so, for 5.7 s
// more of the first build; docs/PERFORMANCE.md, "The student's loop").
// To optimise the course target as well
// (a debug build nearly as fast as a release one), or nothing at all
// (should a toolchain refuse the flag):
//   RAYTRACE_OPTIMIZED_COURSE=1 swift build
//   RAYTRACE_UNOPTIMIZED=1 swift build
let optimizedInDebugBuilds: [SwiftSetting] =
  variable("RAYTRACE_UNOPTIMIZED") != nil
  ? []
  : [.unsafeFlags(["-O"], .when(configuration: .debug))]
let courseSettings: [SwiftSetting] =
  variable("RAYTRACE_OPTIMIZED_COURSE") != nil ? optimizedInDebugBuilds : []

// Release builds optimise across the library's targets: the fast engine's
// generic kernels are specialised for Float and Double with the
// arithmetic of ExactArithmetic and Geometry inlined into them, as when
// they were one module (without it the 10⁴-sphere render was 2.5 times
// slower). Debug builds do not: it
// would cost the student's loop its build time.
let acrossTargets: [SwiftSetting] = [
  .unsafeFlags(["-cross-module-optimization"], .when(configuration: .release))
]

let package = Package(
  name: "raytrace",
  products: [
    .executable(name: "raytrace", targets: ["raytrace"]),
    .library(name: "Course", targets: ["Course"]),
  ],
  dependencies: dependencies,
  // Targets by audience, arrows only downwards (docs/ENGINES.md draws
  // them):
  //   Geometry          vectors, rays, matrices, boxes, hits, the hit
  //                     protocol, camera, lights, materials, textures, the
  //                     image's conventions: the leaf
  //   SceneDescription  the scene as read: plain data, no intersection;
  //                     its one walk over the objects (`forEachPlaced`)
  //   Course            the course's shapes and loop: what a student edits
  //   PlatformSupport   the C library: files, memory, threads, processes
  //   ExactArithmetic   double-double, compensated and exact sums, the
  //                     reference scalar: no scene, no engine
  //   SceneIO           the scene, mesh and image readers and writers
  //   FastKernels       the fast engine's kernels and the scene flattened
  //                     and scaled for it (its length scales)
  //   FastEngine        the fast engine: records, search structures, renders
  //   Pipeline          read, check, render with an engine, encode, commit;
  //                     the default engine, what each engine cannot hold
  //   Measurement       `raytrace report`, `bench`, `compare`, the check
  //                     (beside Pipeline, not above it: SwiftPM starts a
  //                     target only when those below it are compiled)
  //   raytrace          the executable: arguments and messages
  // Scripts/check-layers.py checks that every file imports only what its
  // target declares and that nothing below the pipeline names an engine
  // not its own, an option or what sits above it.
  // Course needs only the leaf and the description: editing it rebuilds
  // only it, its tests, the pipeline, the measurements and the executable.
  targets: standIns + [
    // The system zlib (zlib1g-dev on Debian, part of the SDK on macOS).
    .systemLibrary(
      name: "CZlib",
      providers: [.apt(["zlib1g-dev"]), .brew(["zlib"])]
    ),
    .target(
      name: "Geometry", dependencies: [realModule],
      swiftSettings: acrossTargets + optimizedInDebugBuilds),
    .target(
      name: "SceneDescription", dependencies: ["Geometry"],
      swiftSettings: acrossTargets),
    .target(
      name: "Course",
      dependencies: ["Geometry", "SceneDescription"],
      swiftSettings: courseSettings
    ),
    .target(name: "PlatformSupport", swiftSettings: acrossTargets),
    .target(
      name: "ExactArithmetic", dependencies: ["Geometry", "PlatformSupport"],
      swiftSettings: acrossTargets),
    .target(
      name: "SceneIO",
      dependencies: ["Geometry", "SceneDescription", "PlatformSupport", "CZlib"],
      swiftSettings: acrossTargets),
    // Unoptimised in debug builds, as the description and the readers:
    // its kernels are @inlinable, specialised and optimised where the
    // fast engine calls them.
    .target(
      name: "FastKernels",
      dependencies: [
        "Geometry", "SceneDescription", "ExactArithmetic", "PlatformSupport",
      ],
      swiftSettings: acrossTargets),
    .target(
      name: "FastEngine",
      dependencies: [
        "Geometry", "SceneDescription", "ExactArithmetic", "PlatformSupport",
        "FastKernels",
      ],
      swiftSettings: acrossTargets + optimizedInDebugBuilds),
    .target(
      name: "Pipeline",
      dependencies: [
        "Geometry", "SceneDescription", "Course", "ExactArithmetic", "PlatformSupport",
        "SceneIO", "FastEngine", "FastKernels",
      ],
      swiftSettings: acrossTargets),
    .target(
      name: "Measurement",
      dependencies: [
        "Course", "Geometry", "SceneDescription", "ExactArithmetic", "PlatformSupport", "SceneIO",
        "FastEngine", "FastKernels", realModule,
      ]
    ),
    .executableTarget(
      name: "raytrace",
      dependencies: [
        "Course", "Geometry", "SceneDescription", "ExactArithmetic", "PlatformSupport", "SceneIO",
        "FastEngine", "FastKernels", "Pipeline", "Measurement", argumentParser,
      ]
    ),
    // Helpers more than one test target uses (seeded random numbers,
    // errors in ulps, exact references, the project's files): a library
    // target, as swift-argument-parser's ArgumentParserTestHelpers is.
    .target(
      name: "TestSupport", dependencies: ["Geometry", "ExactArithmetic"],
      path: "Tests/TestSupport", swiftSettings: optimizedInDebugBuilds
    ),
    // One test target per source target, each depending on what it
    // imports; only raytraceTests on the executable.
    .testTarget(
      name: "GeometryTests",
      dependencies: ["Geometry", "ExactArithmetic", "TestSupport"]
    ),
    .testTarget(
      name: "ExactArithmeticTests",
      dependencies: ["ExactArithmetic", "Geometry", "TestSupport"]
    ),
    .testTarget(
      name: "SceneIOTests",
      dependencies: [
        "SceneIO", "Geometry", "SceneDescription", "ExactArithmetic",
        "PlatformSupport", "CZlib", "TestSupport",
        // Hostile scenes are checked as a render places them (`flattened`).
        "FastEngine", "FastKernels",
      ]
    ),
    .testTarget(
      // The fast engine's and its kernels' (FastKernels): the kernels are
      // tested against the reference in Reference/, beside the engine's.
      name: "FastEngineTests",
      dependencies: [
        "FastEngine", "FastKernels", "Geometry", "SceneDescription", "ExactArithmetic", "SceneIO",
        "PlatformSupport", "TestSupport",
        // The length scales' tests measure renders (`AccuracyRender`) and
        // the limits the pipeline words (`CourseEngineLimits`).
        "Measurement", "Pipeline",
      ]
    ),
    .testTarget(
      name: "PipelineTests",
      dependencies: ["Pipeline", "Geometry", "SceneIO", "TestSupport"]
    ),
    // The course's own tests: the course's closure only.
    .testTarget(
      name: "CourseTests",
      dependencies: ["Course", "Geometry", "SceneDescription"]
    ),
    // `raytrace report`, `bench`, `compare`, and the two engines side by
    // side: their agreement and `--check`.
    .testTarget(
      name: "MeasurementTests",
      dependencies: [
        "Measurement", "Course", "Geometry", "SceneDescription", "ExactArithmetic",
        "PlatformSupport", "SceneIO", "FastEngine", "FastKernels", "Pipeline", "TestSupport",
      ]
    ),
    // The command line: runs the executable.
    .testTarget(
      name: "raytraceTests",
      dependencies: [
        "raytrace", "Measurement", "Geometry", "SceneDescription", "ExactArithmetic",
        "PlatformSupport", "SceneIO", "TestSupport",
      ]
    ),
  ]
)
