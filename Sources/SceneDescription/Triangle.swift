import Geometry

/// A triangle (v0, v1, v2), optionally with a normal at each vertex for
/// smooth shading (an OBJ file's `vn`).
///
/// Its normal is the one its winding gives, (v1 − v0) × (v2 − v0)
/// normalised, whichever side a ray comes from: it is not flipped towards
/// the ray, as the 6.837 reference images show back faces with their true
/// normal (and as `Plane` reports its normal as given). With vertex normals,
/// the hit's normal is their barycentric interpolation, normalised, also not
/// flipped.
public struct Triangle<Scalar: RayScalar>: Hashable, Sendable {
  public var v0: Vector3<Scalar>
  public var v1: Vector3<Scalar>
  public var v2: Vector3<Scalar>
  /// Normals at v0, v1 and v2, or nil for flat shading.
  public var vertexNormals: VertexNormals?
  /// Texture coordinates (u, v) at v0, v1 and v2, or nil.
  public var textureCoordinates: TextureCoordinates?
  public var materialIndex: Int

  /// Normals at a triangle's vertices, in the order of its vertices. They
  /// need not be unit length: the interpolation is normalised.
  public struct VertexNormals: Hashable, Sendable {
    public var n0: Vector3<Scalar>
    public var n1: Vector3<Scalar>
    public var n2: Vector3<Scalar>

    public init(
      _ n0: Vector3<Scalar>, _ n1: Vector3<Scalar>, _ n2: Vector3<Scalar>
    ) {
      self.n0 = n0
      self.n1 = n1
      self.n2 = n2
    }
  }

  /// Texture coordinates at a triangle's vertices, in their order.
  public struct TextureCoordinates: Hashable, Sendable {
    public var t0: TextureCoordinate<Scalar>
    public var t1: TextureCoordinate<Scalar>
    public var t2: TextureCoordinate<Scalar>

    public init(
      _ t0: TextureCoordinate<Scalar>, _ t1: TextureCoordinate<Scalar>,
      _ t2: TextureCoordinate<Scalar>
    ) {
      self.t0 = t0
      self.t1 = t1
      self.t2 = t2
    }

    /// The coordinates at barycentrics (u, v, w) of v0, v1 and v2.
    @inlinable
    public func at(u: Scalar, v: Scalar, w: Scalar) -> TextureCoordinate<Scalar>
    {
      TextureCoordinate(
        t0.u * u + t1.u * v + t2.u * w, t0.v * u + t1.v * v + t2.v * w)
    }
  }

  public init(
    _ v0: Vector3<Scalar>, _ v1: Vector3<Scalar>, _ v2: Vector3<Scalar>,
    vertexNormals: VertexNormals? = nil,
    textureCoordinates: TextureCoordinates? = nil, materialIndex: Int = 0
  ) {
    self.v0 = v0
    self.v1 = v1
    self.v2 = v2
    self.vertexNormals = vertexNormals
    self.textureCoordinates = textureCoordinates
    self.materialIndex = materialIndex
  }

  /// Converts each coordinate, rounding to nearest. A triangle that is thin
  /// in the wider precision may become degenerate in the narrower one.
  public init<Other: RayScalar>(_ other: Triangle<Other>) {
    self.init(
      Vector3(other.v0), Vector3(other.v1), Vector3(other.v2),
      vertexNormals: other.vertexNormals.map {
        VertexNormals(Vector3($0.n0), Vector3($0.n1), Vector3($0.n2))
      },
      textureCoordinates: other.textureCoordinates.map {
        TextureCoordinates(
          TextureCoordinate($0.t0), TextureCoordinate($0.t1),
          TextureCoordinate($0.t2))
      },
      materialIndex: other.materialIndex)
  }

  /// The unit normal of the winding, (v1 − v0) × (v2 − v0) normalised, or
  /// nil when the triangle is degenerate (collinear or repeated vertices, or
  /// a non-finite coordinate): such a triangle is never hit.
  ///
  /// The edges are scaled by a power of two (exactly) before the cross
  /// product, so that neither huge nor tiny triangles overflow or underflow
  /// it; each component is then within a few ulps of the largest.
  @inlinable
  public var geometricNormal: Vector3<Scalar>? {
    let e1 = v1 - v0
    let e2 = v2 - v0
    let largest = Swift.max(e1.maxMagnitude, e2.maxMagnitude)
    guard largest > 0, largest.isFinite else { return nil }
    // Clamped so that edges in the subnormal range scale to finite values.
    let scale = Scalar(
      sign: .plus,
      exponent: Swift.min(
        -largest.exponent, Scalar.greatestFiniteMagnitude.exponent),
      significand: 1)
    let normal = (e1 * scale).cross(e2 * scale)
    guard normal.maxMagnitude > 0, normal.isFinite else { return nil }
    return normal.normalized()
  }
}
