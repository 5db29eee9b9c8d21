import RealModule
import FastEngine
import SceneIO
import Geometry
import SceneDescription

/// How far a render's depth and normals are from the reference path's, per
/// pixel and in summary.
///
/// The reference intersects the very rays the render traced (generated in
/// the render's precision, converted exactly) in `ReferenceScalar` (Float80
/// on x86, 64-bit significand; `DoubleDouble`, 106 bits, where there is no
/// Float80) with the stable camera-relative method, its
/// constants computed from the scene's Double values in twice Double's
/// precision. What is measured is therefore the error of the intersection,
/// not a difference in where the camera's rays point.
package struct AccuracyMeasurement: Sendable {
  /// Pixels where both hit something.
  package var comparedHits: Int
  /// max |t − t_ref| / t_ref over compared hits.
  package var maxRelativeError: Double
  /// The 99th percentile of the same.
  package var p99RelativeError: Double
  /// The largest relative error of t away from silhouettes: over pixels
  /// whose eight neighbours in the reference all hit, at depths within 10%
  /// of the pixel's and with normals within 10° of its. Near a silhouette
  /// the ray is almost tangent and t is ill-conditioned (a rounding in the
  /// discriminant moves it by √ε), so the plain maximum measures the
  /// problem rather than the method.
  package var maxInteriorRelativeError: Double
  /// Pixels where one hit and the other missed.
  package var disagreements: Int
  /// The largest angle between normals over compared hits, in degrees.
  package var maxNormalErrorDegrees: Double
  /// Relative error of t per pixel, row 0 at the top: NaN where both
  /// missed, +inf where they disagree.
  package var perPixel: [Double]

  /// Compares `buffers` (depth and normals) with `reference`.
  package init<S: RayScalar, R: RayScalar>(
    _ buffers: RenderBuffers<S>, against reference: RenderBuffers<R>
  ) {
    precondition(buffers.depth.count == reference.depth.count)
    var errors: [Double] = []
    var perPixel = [Double](repeating: .nan, count: buffers.depth.count)
    var disagreements = 0
    var maxAngle = 0.0
    let hasNormals = !buffers.normals.isEmpty && !reference.normals.isEmpty
    // Converted once: the interior test below reads each up to 18 times,
    // and a generic conversion from a DoubleDouble reference is slow.
    let referenceNormals = reference.normals.map { Vector3<Double>($0) }
    for pixel in buffers.depth.indices {
      let t = buffers.depth[pixel]
      let want = reference.depth[pixel]
      switch (t.isFinite, want.isFinite) {
      case (false, false):
        continue
      case (true, true):
        let error = Double((R(t) - want).magnitude / want)
        errors.append(error)
        perPixel[pixel] = error
        if hasNormals {
          maxAngle = Swift.max(
            maxAngle,
            angleInDegrees(
              Vector3<Double>(buffers.normals[pixel]),
              referenceNormals[pixel]))
        }
      default:
        disagreements += 1
        perPixel[pixel] = .infinity
      }
    }
    var interior = 0.0
    let (width, height) = (buffers.width, buffers.height)
    for row in 1..<Swift.max(1, height - 1) {
      pixels: for column in 1..<Swift.max(1, width - 1) {
        let pixel = row * width + column
        let centre = reference.depth[pixel]
        guard centre.isFinite, perPixel[pixel].isFinite else { continue }
        for dy in -1...1 {
          for dx in -1...1 {
            let neighbour = reference.depth[pixel + dy * width + dx]
            guard neighbour.isFinite,
              (neighbour - centre).magnitude <= centre / 10
            else {
              continue pixels
            }
            if hasNormals {
              let a = referenceNormals[pixel]
              let b = referenceNormals[pixel + dy * width + dx]
              // cos 10° = 0.985
              guard a.dot(b) >= 0.985 else { continue pixels }
            }
          }
        }
        interior = Swift.max(interior, perPixel[pixel])
      }
    }
    maxInteriorRelativeError = interior
    errors.sort()
    comparedHits = errors.count
    maxRelativeError = errors.last ?? 0
    p99RelativeError =
      errors.isEmpty
      ? 0 : errors[Swift.min(errors.count - 1, (errors.count * 99) / 100)]
    self.disagreements = disagreements
    maxNormalErrorDegrees = maxAngle
    self.perPixel = perPixel
  }
}

/// The angle between two vectors in degrees, by atan2(|a × b|, a·b): exact
/// for small angles, where acos(a·b) loses half the digits.
func angleInDegrees(_ a: Vector3<Double>, _ b: Vector3<Double>) -> Double {
  let cross = a.cross(b).length
  return Double.atan2(y: cross, x: a.dot(b)) * 180 / .pi
}

/// The report's measure of either render precision's buffers.
extension AnyRenderBuffers {
  package func measured<R: RayScalar>(
    against reference: RenderBuffers<R>
  ) -> AccuracyMeasurement {
    switch self {
    case .float(let buffers): AccuracyMeasurement(buffers, against: reference)
    case .double(let buffers): AccuracyMeasurement(buffers, against: reference)
    }
  }

  /// The unit roundoff's double, ε = 2^−23 or 2^−52: errors are reported
  /// in units of it.
  package var epsilon: Double {
    switch self {
    case .float: Double(Float.ulpOfOne)
    case .double: Double.ulpOfOne
    }
  }
}
