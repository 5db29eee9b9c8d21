import FastEngine
import FastKernels

/// What a row of `raytrace report` measures: one of the fast engine's
/// intersection methods, or the course engine (the student's code: Double,
/// the hit protocol, the scene's own lengths).
package enum ReportedMethod: Hashable, Sendable {
  case fast(IntersectionMethod)
  case course

  /// Naive and stable in the fast engine, then the course engine where it
  /// renders the scene (`precision` Double and the scene in its range).
  package static func all(withCourse: Bool) -> [ReportedMethod] {
    IntersectionMethod.allCases.map { .fast($0) }
      + (withCourse ? [.course] : [])
  }

  /// The name in the table, the CSV and the plot: naive, stable, course.
  package var name: String {
    switch self {
    case .fast(let method): method.rawValue
    case .course: "course"
    }
  }
}
