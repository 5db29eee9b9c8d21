/// A 4×4 matrix applied to column vectors, p′ = M·p: the scene's
/// `Transform` blocks.
///
///     let m = Matrix4<Double>.translation(Vector3(5, 0, 0))
///       * Matrix4.scale(Vector3(5, 0.2, 0.2))
///     m.transformPoint(Vector3(1, 1, 1))  // (10, 0.2, 0.2)
///
/// Design goals, in order: the exact values the course's transforms should
/// have (rotations by multiples of 90° have exact zeros and ones), an inverse
/// that says when it does not exist instead of returning noise, and cheap
/// per-ray helpers.
///
/// Composition follows the 6.837 parser: each transform in a block multiplies
/// the matrix so far on the right (`matrix = matrix * next`), so the first
/// one listed is applied last to the object's points, and a `Transform`
/// holding M draws the object at M·p. A ray is taken into object space by
/// M⁻¹ (`transformPoint` for the origin, `transformDirection` for the
/// direction, left unnormalised so that t is the same in both spaces), and
/// a hit's normal back by `transformNormal`.
///
/// The entries are stored row by row: `m01` is row 0, column 1, and the
/// translation is the last column (`m03`, `m13`, `m23`).
public struct Matrix4<Scalar: RayScalar>: Hashable, Sendable {
  public var m00, m01, m02, m03: Scalar
  public var m10, m11, m12, m13: Scalar
  public var m20, m21, m22, m23: Scalar
  public var m30, m31, m32, m33: Scalar

  /// The sixteen entries in row order: row 0 first.
  @inlinable
  init(
    _ m00: Scalar, _ m01: Scalar, _ m02: Scalar, _ m03: Scalar,
    _ m10: Scalar, _ m11: Scalar, _ m12: Scalar, _ m13: Scalar,
    _ m20: Scalar, _ m21: Scalar, _ m22: Scalar, _ m23: Scalar,
    _ m30: Scalar, _ m31: Scalar, _ m32: Scalar, _ m33: Scalar
  ) {
    (self.m00, self.m01, self.m02, self.m03) = (m00, m01, m02, m03)
    (self.m10, self.m11, self.m12, self.m13) = (m10, m11, m12, m13)
    (self.m20, self.m21, self.m22, self.m23) = (m20, m21, m22, m23)
    (self.m30, self.m31, self.m32, self.m33) = (m30, m31, m32, m33)
  }

  /// The matrix whose rows are the sixteen `entries` in order: the first
  /// four are row 0, `entries[4 * row + column]` is (row, column), as a
  /// matrix is written on paper.
  ///
  /// Not the order of the 6.837 scene block `Matrix4f { … }`: its parser
  /// reads `for j { for i { matrix2(i, j) = readFloat() } }`, and vecmath's
  /// `Matrix4f(i, j)` is row i, column j (column-major storage,
  /// `m_elements[4j + i]`), so the file lists the matrix column by column.
  /// Use `init(columns:)` for that block.
  ///
  /// - Precondition: exactly 16 entries; the scene parser reads exactly 16
  ///   numbers, so any other count is a programming error.
  public init(rows entries: [Scalar]) {
    precondition(entries.count == 16, "a 4×4 matrix has 16 entries")
    self.init(
      entries[0], entries[1], entries[2], entries[3],
      entries[4], entries[5], entries[6], entries[7],
      entries[8], entries[9], entries[10], entries[11],
      entries[12], entries[13], entries[14], entries[15])
  }

  /// The matrix whose columns are the sixteen `entries` in order: the first
  /// four are column 0, `entries[4 * column + row]` is (row, column); the
  /// translation is `entries[12...14]`. The reading order of the 6.837
  /// `Matrix4f { … }` scene block (see `init(rows:)`) and of OpenGL.
  ///
  /// Note for the scene parser: 6.837 composes that block on the left,
  /// `matrix = matrix2 * matrix`, unlike `Translate`, `Scale` and the
  /// rotations, which compose on the right (`matrix = matrix * next`).
  ///
  /// - Precondition: exactly 16 entries.
  public init(columns entries: [Scalar]) {
    precondition(entries.count == 16, "a 4×4 matrix has 16 entries")
    self.init(rows: entries)
    self = transposed()
  }

  /// Converts each entry, rounding to nearest.
  @inlinable
  public init<Other: RayScalar>(_ other: Matrix4<Other>) {
    func c(_ x: Other) -> Scalar { Scalar(x) }
    self.init(
      c(other.m00), c(other.m01), c(other.m02), c(other.m03),
      c(other.m10), c(other.m11), c(other.m12), c(other.m13),
      c(other.m20), c(other.m21), c(other.m22), c(other.m23),
      c(other.m30), c(other.m31), c(other.m32), c(other.m33))
  }

  /// The entry at (row, column), both in 0...3.
  ///
  /// - Precondition: row and column in 0...3.
  package subscript(row: Int, column: Int) -> Scalar {
    get {
      precondition((0..<4).contains(row) && (0..<4).contains(column))
      switch (row, column) {
      case (0, 0): return m00
      case (0, 1): return m01
      case (0, 2): return m02
      case (0, 3): return m03
      case (1, 0): return m10
      case (1, 1): return m11
      case (1, 2): return m12
      case (1, 3): return m13
      case (2, 0): return m20
      case (2, 1): return m21
      case (2, 2): return m22
      case (2, 3): return m23
      case (3, 0): return m30
      case (3, 1): return m31
      case (3, 2): return m32
      default: return m33
      }
    }
    set {
      precondition((0..<4).contains(row) && (0..<4).contains(column))
      switch (row, column) {
      case (0, 0): m00 = newValue
      case (0, 1): m01 = newValue
      case (0, 2): m02 = newValue
      case (0, 3): m03 = newValue
      case (1, 0): m10 = newValue
      case (1, 1): m11 = newValue
      case (1, 2): m12 = newValue
      case (1, 3): m13 = newValue
      case (2, 0): m20 = newValue
      case (2, 1): m21 = newValue
      case (2, 2): m22 = newValue
      case (2, 3): m23 = newValue
      case (3, 0): m30 = newValue
      case (3, 1): m31 = newValue
      case (3, 2): m32 = newValue
      default: m33 = newValue
      }
    }
  }

  /// The sixteen entries row by row, the inverse of `init(rows:)`.
  package var rowMajorEntries: [Scalar] {
    [
      m00, m01, m02, m03, m10, m11, m12, m13,
      m20, m21, m22, m23, m30, m31, m32, m33,
    ]
  }

  /// Whether the last row is exactly (0, 0, 0, 1): every transform the scene
  /// language builds except a general `Matrix4f`.
  @inlinable
  package var isAffine: Bool {
    m30 == 0 && m31 == 0 && m32 == 0 && m33 == 1
  }
}

// MARK: - Building transforms

extension Matrix4 {
  public static var identity: Matrix4 {
    Matrix4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1)
  }

  /// p ↦ p + offset (directions and normals are unchanged).
  public static func translation(_ offset: Vector3<Scalar>) -> Matrix4 {
    Matrix4(
      1, 0, 0, offset.x,
      0, 1, 0, offset.y,
      0, 0, 1, offset.z,
      0, 0, 0, 1)
  }

  /// p ↦ (sx·x, sy·y, sz·z). A zero factor gives a singular matrix (its
  /// `inverse()` is nil); a negative one mirrors, reversing the winding of
  /// transformed triangles.
  public static func scale(_ factors: Vector3<Scalar>) -> Matrix4 {
    Matrix4(
      factors.x, 0, 0, 0,
      0, factors.y, 0, 0,
      0, 0, factors.z, 0,
      0, 0, 0, 1)
  }

  /// p ↦ s·p.
  public static func uniformScale(_ factor: Scalar) -> Matrix4 {
    scale(Vector3(factor, factor, factor))
  }

  /// Rotation about the x axis by `degrees`, counter-clockwise when looking
  /// down the axis towards the origin (right-handed: y turns towards z), as
  /// 6.837's `XRotate` and `Matrix4f::rotateX`: rows (1, 0, 0), (0, c, −s),
  /// (0, s, c).
  ///
  /// Multiples of 90° give exact zeros and ones (see `cosineAndSine`);
  /// other angles are within an ulp or so of the correctly rounded cosine and
  /// sine. A non-finite angle gives NaN entries.
  public static func rotationX(degrees: Scalar) -> Matrix4 {
    let (c, s) = cosineAndSine(degrees: degrees)
    return Matrix4(
      1, 0, 0, 0,
      0, c, -s, 0,
      0, s, c, 0,
      0, 0, 0, 1)
  }

  /// Rotation about the y axis: z turns towards x. Rows (c, 0, s),
  /// (0, 1, 0), (−s, 0, c). See `rotationX(degrees:)`.
  public static func rotationY(degrees: Scalar) -> Matrix4 {
    let (c, s) = cosineAndSine(degrees: degrees)
    return Matrix4(
      c, 0, s, 0,
      0, 1, 0, 0,
      -s, 0, c, 0,
      0, 0, 0, 1)
  }

  /// Rotation about the z axis: x turns towards y. Rows (c, −s, 0),
  /// (s, c, 0), (0, 0, 1). See `rotationX(degrees:)`.
  public static func rotationZ(degrees: Scalar) -> Matrix4 {
    let (c, s) = cosineAndSine(degrees: degrees)
    return Matrix4(
      c, -s, 0, 0,
      s, c, 0, 0,
      0, 0, 1, 0,
      0, 0, 0, 1)
  }

  /// cos and sin of an angle in degrees, with the angle reduced exactly
  /// before converting to radians: r = degrees mod 360 (`remainder` is
  /// exact), then r = 90·q + ρ with |ρ| ≤ 45 (exact: the subtraction's
  /// operands are within a factor of two, or ρ lies on their grid), and the
  /// result is read off the quadrant q. So 90°, 180°, −270° and 3600° give
  /// exactly 0 and ±1, where cos(90·π/180) would give 6e−17, and the error
  /// of ρ·π/180 stays relative to ρ rather than to the whole angle.
  @usableFromInline
  package static func cosineAndSine(degrees: Scalar)
    -> (cos: Scalar, sin: Scalar)
  {
    guard degrees.isFinite else { return (.nan, .nan) }
    let reduced = degrees.remainder(dividingBy: 360)
    let quadrant = (reduced / 90).rounded()
    let rest = reduced - 90 * quadrant
    let radians = rest * (Scalar.pi / 180)
    let c = Scalar.cos(radians)
    let s = Scalar.sin(radians)
    switch quadrant {
    case 0: return (c, s)
    // cos(ρ + 90°) = −sin ρ, sin(ρ + 90°) = cos ρ.
    case 1: return (-s, c)
    case -1: return (s, -c)
    default: return (-c, -s)
    }
  }
}

// MARK: - Arithmetic

extension Matrix4 {
  /// The product a·b: applying it applies b first, then a.
  @inlinable
  public static func * (a: Matrix4, b: Matrix4) -> Matrix4 {
    Matrix4(
      a.m00 * b.m00 + a.m01 * b.m10 + a.m02 * b.m20 + a.m03 * b.m30,
      a.m00 * b.m01 + a.m01 * b.m11 + a.m02 * b.m21 + a.m03 * b.m31,
      a.m00 * b.m02 + a.m01 * b.m12 + a.m02 * b.m22 + a.m03 * b.m32,
      a.m00 * b.m03 + a.m01 * b.m13 + a.m02 * b.m23 + a.m03 * b.m33,
      a.m10 * b.m00 + a.m11 * b.m10 + a.m12 * b.m20 + a.m13 * b.m30,
      a.m10 * b.m01 + a.m11 * b.m11 + a.m12 * b.m21 + a.m13 * b.m31,
      a.m10 * b.m02 + a.m11 * b.m12 + a.m12 * b.m22 + a.m13 * b.m32,
      a.m10 * b.m03 + a.m11 * b.m13 + a.m12 * b.m23 + a.m13 * b.m33,
      a.m20 * b.m00 + a.m21 * b.m10 + a.m22 * b.m20 + a.m23 * b.m30,
      a.m20 * b.m01 + a.m21 * b.m11 + a.m22 * b.m21 + a.m23 * b.m31,
      a.m20 * b.m02 + a.m21 * b.m12 + a.m22 * b.m22 + a.m23 * b.m32,
      a.m20 * b.m03 + a.m21 * b.m13 + a.m22 * b.m23 + a.m23 * b.m33,
      a.m30 * b.m00 + a.m31 * b.m10 + a.m32 * b.m20 + a.m33 * b.m30,
      a.m30 * b.m01 + a.m31 * b.m11 + a.m32 * b.m21 + a.m33 * b.m31,
      a.m30 * b.m02 + a.m31 * b.m12 + a.m32 * b.m22 + a.m33 * b.m32,
      a.m30 * b.m03 + a.m31 * b.m13 + a.m32 * b.m23 + a.m33 * b.m33)
  }

  @inlinable
  public static func *= (a: inout Matrix4, b: Matrix4) { a = a * b }

  /// Rows and columns exchanged.
  @inlinable
  public func transposed() -> Matrix4 {
    Matrix4(
      m00, m10, m20, m30,
      m01, m11, m21, m31,
      m02, m12, m22, m32,
      m03, m13, m23, m33)
  }
}
