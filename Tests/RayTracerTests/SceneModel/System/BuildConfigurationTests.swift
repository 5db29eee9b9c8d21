import XCTest

@testable import FastEngine
@testable import Measurement
@testable import SceneIO
@testable import SceneModel

final class BuildConfigurationTests: XCTestCase {
  /// Debug builds (Package.swift) must keep the library's
  /// assertions, which the tests rely on; release builds drop them.
  func testAssertions_CheckedExactlyInDebugBuilds() {
    #if DEBUG
      XCTAssertTrue(BuildConfiguration.checksAssertions)
    #else
      XCTAssertFalse(BuildConfiguration.checksAssertions)
    #endif
  }
}
