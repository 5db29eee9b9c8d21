import Course
import Measurement
import Geometry
import XCTest

// The lecture's shapes as the slides write them (the textbook quadratic,
// the plane's t, Cramer's rule, the ray taken into object space), each
// with one common mistake that can be switched on: the shapes
// `ShapeProbeTests` hands to the probes.

/// The slide's sphere: a = d·d, b = 2 f·d, c = f·f − r²,
/// t = (−b ∓ √(b² − 4ac)) / 2a, normal (P − center) / r.
struct SlideSphere: Hittable {
  enum Mistake {
    case none, centreForgotten, farRoot, nearRootWhatever
    case noDiscriminantTest, discriminantPositive, nearRootOnly
    case directionNormalised, aIsOne, normalNotNormalised, normalIn
  }

  var center: Vector3<Double>
  var radius: Double
  var materialIndex: Int
  var mistake: Mistake

  func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    let d =
      mistake == .directionNormalised
      ? ray.direction.normalized() : ray.direction
    let f = mistake == .centreForgotten ? ray.origin : ray.origin - center
    let a = mistake == .aIsOne ? 1 : d.dot(d)
    let b = 2 * f.dot(d)
    let c = f.dot(f) - radius * radius
    let discriminant = b * b - 4 * a * c
    switch mistake {
    case .noDiscriminantTest: break
    case .discriminantPositive: guard discriminant > 0 else { return nil }
    default: guard discriminant >= 0 else { return nil }
    }
    let near = (-b - discriminant.squareRoot()) / (2 * a)
    let far = (-b + discriminant.squareRoot()) / (2 * a)
    let t: Double
    switch mistake {
    case .farRoot:
      t = far
      guard tMin < t, t < tMax else { return nil }
    case .nearRootWhatever:
      t = near
      guard t < tMax else { return nil }
    case .nearRootOnly:
      t = near
      guard tMin < t, t < tMax else { return nil }
    case .noDiscriminantTest:
      t = tMin < near ? near : far
      if t <= tMin || t >= tMax { return nil }  // NaN passes
    default:
      t = tMin < near ? near : far
      guard tMin < t, t < tMax else { return nil }
    }
    let out = f + d * t
    let normal: Vector3<Double>
    switch mistake {
    case .normalNotNormalised: normal = out
    case .normalIn: normal = -out.normalized()
    default: normal = out.normalized()
    }
    return Hit(t: t, normal: normal, materialIndex: materialIndex)
  }

  var boundingBox: BoundingBox? {
    let reach = Vector3(radius, radius, radius)
    return BoundingBox(lower: center - reach, upper: center + reach)
  }
}

/// The slide's plane n·P = offset: t = (offset − n·o) / (n·d).
struct SlidePlane: Hittable {
  enum Mistake {
    case none, offsetFlipped, oneSided, normalTowardsTheRay, tMinOnly
    case intervalByExclusion, directionNormalised
  }

  var normal: Vector3<Double>
  var offset: Double
  var materialIndex: Int
  var mistake: Mistake

  func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    let d =
      mistake == .directionNormalised
      ? ray.direction.normalized() : ray.direction
    let offset = mistake == .offsetFlipped ? -self.offset : self.offset
    let along = normal.dot(d)
    if mistake == .oneSided, along >= 0 { return nil }
    let t = (offset - normal.dot(ray.origin)) / along
    switch mistake {
    case .tMinOnly: guard t > tMin else { return nil }
    case .intervalByExclusion: if t <= tMin || t >= tMax { return nil }
    default: guard tMin < t, t < tMax else { return nil }
    }
    let turned = mistake == .normalTowardsTheRay && along > 0
    return Hit(
      t: t, normal: turned ? -normal : normal, materialIndex: materialIndex)
  }

  var boundingBox: BoundingBox? { nil }
}

/// The slide's triangle: β, γ and t by Cramer's rule.
struct CramerTriangle: Hittable {
  enum Mistake {
    case none, noBetaTest, noGammaTest, noSumTest, culled, windingReversed
    case flatNormal, noTexture, weightsSwapped, directionNormalised
  }

  var corners: ProbedTriangle
  var mistake: Mistake

  func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    let d =
      mistake == .directionNormalised
      ? ray.direction.normalized() : ray.direction
    let (a, b, c) = (corners.a, corners.b, corners.c)
    let edge1 = b - a
    let edge2 = c - a
    let p = d.cross(edge2)
    let determinant = edge1.dot(p)
    if mistake == .culled {
      guard determinant > 0 else { return nil }
    } else {
      guard determinant != 0 else { return nil }
    }
    let s = ray.origin - a
    let q = s.cross(edge1)
    let beta = s.dot(p) / determinant
    let gamma = d.dot(q) / determinant
    let t = edge2.dot(q) / determinant
    guard mistake == .noBetaTest || beta >= 0,
      mistake == .noGammaTest || gamma >= 0,
      mistake == .noSumTest || beta + gamma <= 1, tMin < t, t < tMax
    else { return nil }
    let alpha = 1 - beta - gamma
    let (wa, wb, wc) =
      mistake == .weightsSwapped ? (alpha, gamma, beta) : (alpha, beta, gamma)
    var normal =
      mistake == .windingReversed ? edge2.cross(edge1) : edge1.cross(edge2)
    if let (n0, n1, n2) = corners.normals, mistake != .flatNormal {
      normal = n0 * wa + n1 * wb + n2 * wc
    }
    var hit = Hit(
      t: t, normal: normal.normalized(),
      materialIndex: corners.materialIndex)
    if let (t0, t1, t2) = corners.textureCoordinates, mistake != .noTexture {
      hit.textureCoordinate = TextureCoordinate(
        t0.u * wa + t1.u * wb + t2.u * wc, t0.v * wa + t1.v * wb + t2.v * wc)
    }
    return hit
  }

  var boundingBox: BoundingBox? {
    BoundingBox(around: corners.a, corners.b, corners.c)
  }
}

/// The slide's transform: the ray into object space by M⁻¹, the normal
/// back by (M⁻¹)ᵀ.
struct SlideTransform: Hittable {
  enum Mistake {
    case none, normalByMatrix, normalByInverse, normalUnmoved
    case normalNotNormalised, objectDirectionNormalised, originAsDirection
    case worldDirectionNormalised
  }

  var matrix: Matrix4<Double>
  var inverse: Matrix4<Double>
  var object: any Hittable
  var mistake: Mistake

  init?(matrix: Matrix4<Double>, object: any Hittable, mistake: Mistake) {
    guard let inverse = matrix.inverse() else { return nil }
    self.matrix = matrix
    self.inverse = inverse
    self.object = object
    self.mistake = mistake
  }

  func intersect(
    _ ray: Ray<Double>, after tMin: Double, before tMax: Double
  ) -> Hit<Double>? {
    let d =
      mistake == .worldDirectionNormalised
      ? ray.direction.normalized() : ray.direction
    let origin =
      mistake == .originAsDirection
      ? inverse.transformDirection(ray.origin)
      : inverse.transformPoint(ray.origin)
    var direction = inverse.transformDirection(d)
    if mistake == .objectDirectionNormalised {
      direction = direction.normalized()
    }
    guard
      var hit = object.intersect(
        Ray(origin: origin, direction: direction), after: tMin, before: tMax)
    else { return nil }
    let n = hit.normal
    switch mistake {
    case .normalByMatrix:
      hit.normal = matrix.transformDirection(n).normalized()
    case .normalByInverse:
      hit.normal = inverse.transformDirection(n).normalized()
    case .normalUnmoved: break
    case .normalNotNormalised:
      hit.normal = inverse.transposed().transformDirection(n)
    default:
      hit.normal = inverse.transposed().transformDirection(n).normalized()
    }
    return hit
  }

  var boundingBox: BoundingBox? {
    object.boundingBox?.transformed(by: matrix)
  }
}

/// Factories of the slides' shapes, each with its mistake.
func slideSphere(_ mistake: SlideSphere.Mistake)
  -> (Vector3<Double>, Double, Int) -> any Hittable
{
  { SlideSphere(center: $0, radius: $1, materialIndex: $2, mistake: mistake) }
}

func slidePlane(_ mistake: SlidePlane.Mistake)
  -> (Vector3<Double>, Double, Int) -> any Hittable
{
  { SlidePlane(normal: $0, offset: $1, materialIndex: $2, mistake: mistake) }
}

func cramerTriangle(_ mistake: CramerTriangle.Mistake)
  -> (ProbedTriangle) -> any Hittable
{
  { CramerTriangle(corners: $0, mistake: mistake) }
}

func slideTransform(_ mistake: SlideTransform.Mistake)
  -> (Matrix4<Double>, any Hittable) -> (any Hittable)?
{
  { SlideTransform(matrix: $0, object: $1, mistake: mistake) }
}

func factories(
  sphere: SlideSphere.Mistake, plane: SlidePlane.Mistake,
  triangle: CramerTriangle.Mistake, transform: SlideTransform.Mistake
) -> ShapeFactories {
  ShapeFactories(
    sphere: slideSphere(sphere), plane: slidePlane(plane),
    triangle: cramerTriangle(triangle), transform: slideTransform(transform))
}
