// swift-tools-version:6.0
import Foundation
import PackageDescription

// The course's closure alone, for Scripts/check-handouts.sh: the stand-in
// for swift-numerics, Geometry, SceneDescription, Course and CourseTests,
// with the settings the repository's Package.swift gives them, so that
// each week's handout is built and tested without the rest of the
// package. The script copies the sources in beside this file; keep the
// settings below in step with Package.swift's (check-handouts.sh fails
// when they drift).
let environment = ProcessInfo.processInfo.environment

func variable(_ name: String) -> String? {
  guard let value = environment[name], !value.isEmpty else { return nil }
  return value
}

let optimizedInDebugBuilds: [SwiftSetting] =
  variable("RAYTRACE_UNOPTIMIZED") != nil
  ? []
  : [.unsafeFlags(["-O"], .when(configuration: .debug))]
let courseSettings: [SwiftSetting] =
  variable("RAYTRACE_OPTIMIZED_COURSE") != nil ? optimizedInDebugBuilds : []
let acrossTargets: [SwiftSetting] = [
  .unsafeFlags(["-cross-module-optimization"], .when(configuration: .release))
]

let package = Package(
  name: "course-handouts",
  targets: [
    .target(name: "RealModule"),
    .target(
      name: "Geometry", dependencies: ["RealModule"],
      swiftSettings: acrossTargets + optimizedInDebugBuilds),
    .target(
      name: "SceneDescription", dependencies: ["Geometry"],
      swiftSettings: acrossTargets),
    .target(
      name: "Course",
      dependencies: ["Geometry", "SceneDescription"],
      swiftSettings: courseSettings
    ),
    .testTarget(
      name: "CourseTests",
      dependencies: ["Course", "Geometry", "SceneDescription"]
    ),
  ]
)
