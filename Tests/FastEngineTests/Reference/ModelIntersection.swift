@testable import FastEngine
@testable import FastKernels
@testable import Geometry
@testable import SceneDescription
@testable import ExactArithmetic
@testable import SceneIO
@testable import PlatformSupport
import TestSupport

// The scene description intersected directly, by the fast engine's own
// numerics (`SphereIntersection`, `PlaneIntersection`,
// `TriangleIntersection`, `EllipsoidFrame`): the reference the tests hold
// the compiled scene's records to, bit for bit. A measuring instrument of
// the tests, not a third model of the shapes: nothing in Sources calls it.

/// Anything the reference can hit, by either method.
protocol Intersectable<Scalar> {
  associatedtype Scalar: RayScalar

  /// The nearest hit with tMin < t < tMax by `method`, or nil. A tie
  /// (two surfaces at the same t) goes to the one tested first.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>?
}

extension Intersectable {
  /// The nearest hit with tMin < t < tMax by the stable method, or nil.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar
  ) -> Hit<Scalar>? {
    intersect(ray, after: tMin, before: tMax, method: .stable)
  }
}

extension Sphere: Intersectable {
  /// The nearest hit in (tMin, tMax) by the given method.
  ///
  /// Misses return nil; a tangent ray hits at its double root; a ray from
  /// inside (or from the surface, with tMin = 0) hits the far side. The
  /// normal is outward and unit length. The stable method's relative error
  /// of t is a few ulps away from the silhouette, whatever the ratio of
  /// distance to radius (see the stiff suite).
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    switch method {
    case .naive:
      guard
        let t = SphereIntersection.naiveRoot(
          origin: ray.origin, direction: ray.direction, center: center,
          radius: radius, after: tMin, before: tMax)
      else { return nil }
      let normal = SphereIntersection.naiveNormal(
        origin: ray.origin, direction: ray.direction, center: center, t: t)
      return Hit(t: t, normal: normal, materialIndex: materialIndex)
    case .stable:
      // The sphere as seen from the ray's origin: p = centre − o and
      // c = |p|² − r², each rounded once.
      let relative = CameraRelative.sphere(
        center: center, radius: radius, eye: ray.origin, as: Scalar.self)
      let a = ray.direction.lengthSquared
      let inverseA = SphereIntersection.inverseLengthSquared(a)
      let radiusSquared = radius * radius
      guard
        let root = SphereIntersection.stableRoot(
          direction: ray.direction, lengthSquared: a,
          inverseLengthSquared: inverseA, offset: relative.offset,
          c: relative.c, radiusSquared: radiusSquared,
          after: tMin, before: tMax)
      else { return nil }
      let normal = SphereIntersection.stableNormal(
        direction: ray.direction, lengthSquared: a,
        inverseLengthSquared: inverseA, t: root.t,
        offset: relative.offset, c: relative.c, radiusSquared: radiusSquared,
        inverseRadius: 1 / radius, entering: root.entering)
      return Hit(t: root.t, normal: normal, materialIndex: materialIndex)
    }
  }
}

extension Plane: Intersectable {
  /// The hit in (tMin, tMax), or nil: a ray parallel to the plane (n·d = 0)
  /// misses it, as does a ray starting on it (t = 0 is not > tMin ≥ 0).
  ///
  /// The stable method takes the plane relative to the ray's origin,
  /// k = d − n·o without cancellation, and n·d compensated at grazing
  /// angles (`PlaneIntersection.stableT`).
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    let t: Scalar?
    switch method {
    case .naive:
      t = PlaneIntersection.naiveT(
        normal: normal, offset: offset, origin: ray.origin,
        direction: ray.direction, after: tMin, before: tMax)
    case .stable:
      let distance: Scalar = CameraRelative.plane(
        normal: normal, offset: offset, eye: ray.origin)
      t = PlaneIntersection.stableT(
        normal: normal, normalTail: .zero, distance: distance,
        isAxisAligned: PlaneIntersection.isAxisAligned(normal),
        direction: ray.direction, after: tMin, before: tMax)
    }
    return t.map { Hit(t: $0, normal: normal, materialIndex: materialIndex) }
  }
}

extension Triangle: Intersectable {
  /// The hit in (tMin, tMax), or nil, by `TriangleIntersection`'s watertight
  /// test.
  ///
  /// Hits from either side, with the normal as wound (not flipped); a ray
  /// through an edge or a vertex hits; a ray parallel to the triangle's
  /// plane misses, as do degenerate triangles (`isDegenerate`). With the
  /// stable method t is within 2 + 5/cos θ ulps of the exact intersection
  /// for any size and shape: large and thin triangles take it from their
  /// exact plane (`exactPlane`; contract and measurements in
  /// docs/ACCURACY.md, "Triangles of any size and shape").
  ///
  /// Both methods run the same test; they differ in the geometric normal,
  /// which the stable method takes from the vertices relative to the
  /// ray's origin (as the watertight test sees them) and the naive one
  /// from the vertices as given.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    let seen =
      method == .naive
      ? self
      : Triangle(v0 - ray.origin, v1 - ray.origin, v2 - ray.origin)
    // The watertight test decides; the stable method's exact plane, where
    // the triangle has one, gives t, and is found only for rays the edges
    // accept (`TriangleIntersection.intersect(_:_:after:before:exactPlane:)`).
    let prepared = WatertightRay(ray)
    guard
      let hit = TriangleIntersection.intersect(
        prepared, PermutedTriangle(prepared, v0, v1, v2), after: tMin,
        before: tMax,
        exactPlane: {
          guard method == .stable, let geometric = seen.geometricNormal
          else { return nil }
          return exactPlane(seen: seen, geometric: geometric, from: ray.origin)
        }),
      let geometric = seen.geometricNormal
    else { return nil }
    let t = hit.t
    let normal = shadingNormal(
      u: hit.u, v: hit.v, w: hit.w, geometric: geometric)
    return Hit(
      t: t, normal: normal, materialIndex: materialIndex,
      textureCoordinate: textureCoordinates?.at(u: hit.u, v: hit.v, w: hit.w))
  }

  /// The plane the stable method takes t from, as the fast engine's
  /// compiled triangles do: for a triangle large beside its distance from
  /// `origin` (`TrianglePlane.make`) or whose watertight t would lose
  /// digits (`TrianglePlane.needsExactT`), its exact plane
  /// (`TrianglePlane.exact`, from the vertices as Doubles: exact for Float
  /// and Double triangles; a wider type keeps the large triangles' plane
  /// in its own precision); nil for every other triangle.
  func exactPlane(
    seen: Triangle, geometric: Vector3<Scalar>, from origin: Vector3<Scalar>
  ) -> TrianglePlane.Exact<Scalar>? {
    let relative = (seen.v0, seen.v1, seen.v2)
    let large = TrianglePlane.make(
      relative: relative, normal: geometric, v0: v0, origin: origin)
    guard large != nil || TrianglePlane.needsExactT(relative: relative)
    else { return nil }
    if Scalar.significandBitCount <= Double.significandBitCount,
      let exact = TrianglePlane.exact(
        Vector3<Double>(v0), Vector3<Double>(v1), Vector3<Double>(v2),
        origin: Vector3<Double>(origin), as: Scalar.self)
    {
      return exact
    }
    return large.map {
      TrianglePlane.Exact(
        normal: $0.normal, normalTail: .zero, distance: $0.distance,
        isAxisAligned: PlaneIntersection.isAxisAligned($0.normal))
    }
  }
}

extension TriangleMesh: Intersectable {
  /// The nearest hit among the triangles, as a group's (`nearestHit`): a
  /// tie goes to the earlier triangle.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    nearestHit(ray, after: tMin, before: tMax, method: method)
  }
}

extension SceneObject: Intersectable {
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    switch self {
    case .sphere(let sphere):
      sphere.intersect(ray, after: tMin, before: tMax, method: method)
    case .plane(let plane):
      plane.intersect(ray, after: tMin, before: tMax, method: method)
    case .triangle(let triangle):
      triangle.intersect(ray, after: tMin, before: tMax, method: method)
    case .mesh(let mesh):
      mesh.intersect(ray, after: tMin, before: tMax, method: method)
    case .group(let group):
      group.intersect(ray, after: tMin, before: tMax, method: method)
    case .transform(let transform):
      transform.intersect(ray, after: tMin, before: tMax, method: method)
    case .shape(let shape):
      shape.object.intersect(
        Ray(origin: Vector3(ray.origin), direction: Vector3(ray.direction)),
        after: Double(tMin), before: Double(tMax)
      ).map {
        Hit(
          t: Scalar($0.t), normal: Vector3($0.normal),
          materialIndex: $0.materialIndex,
          textureCoordinate: $0.textureCoordinate.map(TextureCoordinate.init))
      }
    }
  }
}

extension Group: Intersectable {
  /// The nearest hit among the objects (`nearestHit`).
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    objects.nearestHit(ray, after: tMin, before: tMax, method: method)
  }
}

extension Sequence where Element: Intersectable {
  /// The nearest hit among the elements, tested in order; each later one
  /// only has to beat the nearest so far (strictly: a tie goes to the
  /// earlier one). A group's objects and a mesh's triangles are searched
  /// this way.
  func nearestHit(
    _ ray: Ray<Element.Scalar>, after tMin: Element.Scalar,
    before tMax: Element.Scalar, method: IntersectionMethod
  ) -> Hit<Element.Scalar>? {
    var nearest: Hit<Element.Scalar>?
    for object in self {
      if let hit = object.intersect(
        ray, after: tMin, before: nearest?.t ?? tMax, method: method)
      {
        nearest = hit
      }
    }
    return nearest
  }
}

extension Transform: Intersectable {
  /// The nearest hit of the placed object. Placing it costs a pass over
  /// the object for every ray: the course engine's price for testing the
  /// scene as the file describes it.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    Group([.transform(self)]).flattened().intersect(
      ray, after: tMin, before: tMax, method: method)
  }
}

extension TransformedSphere: Intersectable {
  /// The stable method: the ellipsoid in the frame of its axes as seen
  /// from the ray's origin (`EllipsoidFrame`, its constants in
  /// DoubleDouble from the Double matrix), tMin ≥ 0: the fast engine's
  /// numbers in Double (in Float it keeps the object-space test for mild
  /// ellipsoids, `StableEllipsoid`). The naive method, the course's way:
  /// the ray taken into the sphere's space by M⁻¹, the sphere's normal
  /// brought back by the inverse transpose.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    if method == .stable {
      let placed = TransformedSphere<Double>(
        sphere: Sphere(
          center: Vector3(sphere.center), radius: Double(sphere.radius),
          materialIndex: sphere.materialIndex),
        matrix: Matrix4(matrix), inverse: Matrix4(inverse))
      let frame = EllipsoidFrame<Scalar>(placed, eye: Vector3(ray.origin))
      guard
        let t = frame.root(
          direction: ray.direction, after: tMin, before: tMax)
      else { return nil }
      return Hit(
        t: t, normal: frame.normal(direction: ray.direction, t: t),
        materialIndex: sphere.materialIndex)
    }
    let local = Ray(
      origin: inverse.transformPoint(ray.origin),
      direction: inverse.transformDirection(ray.direction))
    guard
      var hit = sphere.intersect(
        local, after: tMin, before: tMax, method: method)
    else { return nil }
    hit.normal = matrix.transformNormal(hit.normal)
    return hit
  }
}

extension Primitives: Intersectable {
  /// The nearest hit, kind by kind as the fast engine tests them: spheres,
  /// planes, triangles, then ellipsoids, each in order.
  func intersect(
    _ ray: Ray<Scalar>, after tMin: Scalar, before tMax: Scalar,
    method: IntersectionMethod
  ) -> Hit<Scalar>? {
    var nearest: Hit<Scalar>?
    func test(_ object: some Intersectable<Scalar>) {
      if let hit = object.intersect(
        ray, after: tMin, before: nearest?.t ?? tMax, method: method)
      {
        nearest = hit
      }
    }
    spheres.forEach(test)
    planes.forEach(test)
    triangles.forEach(test)
    transformedSpheres.forEach(test)
    for shape in shapes {
      test(SceneObject<Scalar>.shape(Shape(WorldShape(shape))))
    }
    return nearest
  }
}
