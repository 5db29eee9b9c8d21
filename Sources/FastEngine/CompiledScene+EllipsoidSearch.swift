import FastKernels
import Geometry
import SceneDescription

/// The ellipsoids' search: one by one, or through a hierarchy of their
/// own when there are many, left where they are in `ellipsoids` and reached
/// through its `order`. Tested one by one, 2,000 of them made this engine
/// 7 times slower than a loop over every object (docs/PERFORMANCE.md,
/// "Hierarchies").
extension CompiledScene {
  /// Ellipsoids from which they are searched through their hierarchy.
  static var ellipsoidHierarchyThreshold: Int { 8 }

  /// The box that holds every point at which the kernel can report a hit
  /// on `ellipsoid` (in the coordinates of `eye`), in the rays' frame, or
  /// nil when it is not finite.
  ///
  /// The ellipsoid is {c + L·u : |u| = r}: along axis i it reaches
  /// r·|row i of L| from c, exactly. Its test works in the sphere's space
  /// (or the frame of its axes, the same up to a rotation), where a kernel
  /// reports hits within the sphere hierarchy's reach of the centre
  /// (`BoundingVolumeHierarchy.reach`: r plus a few ε of the eye's
  /// distance there for the stable method, √(r² + γ·D²) for the textbook
  /// one), brought back by L. Carrying the direction there rounds it by
  /// about ε times the aspect κ = A/a, moving a point by ε·κ·(|c − e| + A)
  /// in the world (A the longest semi-axis, at most r·‖L‖_F; κ at most
  /// ‖L‖_F³/|det L|, which is what is used): the box is padded by 64
  /// times that, and by 4 ε of every coordinate it is made of for its
  /// conversion to the render's precision.
  static func ellipsoidBox(
    _ ellipsoid: TransformedSphere<Double>, eye: Vector3<Double>,
    rayOrigin: Vector3<Scalar>
  ) -> (lower: Vector3<Scalar>, upper: Vector3<Scalar>)? {
    let m = ellipsoid.matrix
    let rows = (
      Vector3(m.m00, m.m01, m.m02), Vector3(m.m10, m.m11, m.m12),
      Vector3(m.m20, m.m21, m.m22)
    )
    let r = ellipsoid.sphere.radius.magnitude
    let model: BoundingVolumeHierarchy<Scalar>.ErrorModel =
      Kernel.self == StableKernel<Scalar>.self ? .cancellationFree : .textbook
    let objectEye = ellipsoid.inverse.transformPoint(eye)
    let reached = Double(
      BoundingVolumeHierarchy<Scalar>.reach(
        radius: Scalar(r),
        distance: Scalar((objectEye - ellipsoid.sphere.center).length),
        model: model))
    let norms = Vector3(rows.0.length, rows.1.length, rows.2.length)
    let frobenius = norms.length * r
    let determinant = rows.0.dot(rows.1.cross(rows.2)).magnitude * r * r * r
    let aspect = frobenius * frobenius * frobenius / determinant
    let center = m.transformPoint(ellipsoid.sphere.center)
    let origin = Vector3<Double>(rayOrigin)
    let relative = center - eye + origin
    let epsilon = Double(Scalar.ulpOfOne)
    let pad =
      64 * epsilon * aspect * ((center - eye).length + frobenius)
      + 4 * epsilon
      * (relative.maxMagnitude + origin.maxMagnitude + eye.maxMagnitude
        + frobenius)
    let reach = norms * reached + Vector3(pad, pad, pad)
    let box = (
      lower: Vector3<Scalar>(relative - reach),
      upper: Vector3<Scalar>(relative + reach)
    )
    guard
      [
        box.lower.x, box.lower.y, box.lower.z, box.upper.x, box.upper.y,
        box.upper.z,
      ].allSatisfy(\.isFinite)
    else { return nil }
    return box
  }

  /// Builds the ellipsoids' hierarchy over `transformed` (the spheres
  /// `ellipsoids` were compiled from, in the coordinates of `eye`) when
  /// they are many and every box is finite.
  mutating func buildEllipsoidHierarchy(
    _ transformed: [TransformedSphere<Double>], eye: Vector3<Double>
  ) {
    guard transformed.count >= Self.ellipsoidHierarchyThreshold else {
      return
    }
    var boxes: [(lower: Vector3<Scalar>, upper: Vector3<Scalar>)] = []
    boxes.reserveCapacity(transformed.count)
    for ellipsoid in transformed {
      guard
        let box = Self.ellipsoidBox(ellipsoid, eye: eye, rayOrigin: rayOrigin)
      else { return }
      boxes.append(box)
    }
    let bvh = BoundingVolumeHierarchy<Scalar>(boxes: boxes, threads: threads)
    ellipsoidHierarchy = bvh
    wideEllipsoidHierarchy = WideHierarchy(bvh, rayOrigin: rayOrigin)
  }

  /// `testEllipsoids` through their hierarchy: its nearest, first in order
  /// among equal t (the answer of testing each in order with a strict
  /// `<`). Out of line: inlined into every pixel's search, the traversal
  /// made the 10⁴-sphere render a third slower.
  @inline(never)
  func searchEllipsoids(
    _ ray: CameraRay<Scalar>, _ nearest: inout NearestHit<Scalar, Nearest>
  ) {
    guard let hierarchy = ellipsoidHierarchy else { return }
    ellipsoids.withUnsafeBufferPointer { records in
      hierarchy.order.withUnsafeBufferPointer { order in
        let leaves = EllipsoidLeaves<Kernel>(
          records: records, order: order, ray: ray)
        if let hit = hierarchy.nearest(
          ray, before: nearest.t, leaves: leaves, wide: wideEllipsoidHierarchy)
        {
          nearest.test(.ellipsoid(Int(order[hit.index]))) { _ in hit.t }
        }
      }
    }
  }
}

/// The ellipsoids as their hierarchy's leaves reach them: position p is
/// ellipsoid `order[p]`, tested against one camera ray.
struct EllipsoidLeaves<Kernel: IntersectionKernel>: LeafPrimitives {
  typealias Scalar = Kernel.Scalar
  let records: UnsafeBufferPointer<Kernel.EllipsoidRecord>
  let order: UnsafeBufferPointer<Int32>
  let ray: CameraRay<Scalar>

  @inline(__always)
  func intersect(_ position: Int, before tMax: Scalar) -> Scalar? {
    Kernel.intersect(records[Int(order[position])], ray, before: tMax)
  }
}
