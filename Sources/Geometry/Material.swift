import RealModule

/// A Phong material (the course's `Material` and `PhongMaterial` are the same).
public struct Material<Scalar: RayScalar>: Hashable, Sendable {
  public var diffuse: RGB<Scalar>
  public var specular: RGB<Scalar>
  public var shininess: Scalar
  /// The texture file a textured material names, resolved against the
  /// scene's folder; read only when a shaded image is rendered.
  public var texturePath: String?

  /// White and matte: the course's default when a scene has no materials.
  public static var defaultWhite: Material {
    Material(diffuse: Vector3(1, 1, 1))
  }

  public init(
    diffuse: RGB<Scalar>, specular: RGB<Scalar> = .zero, shininess: Scalar = 0,
    texturePath: String? = nil
  ) {
    self.diffuse = diffuse
    self.specular = specular
    self.shininess = shininess
    self.texturePath = texturePath
  }

  public init<Other: RayScalar>(_ other: Material<Other>) {
    self.init(
      diffuse: Vector3(other.diffuse), specular: Vector3(other.specular),
      shininess: Scalar(other.shininess), texturePath: other.texturePath)
  }

  /// What the shading formula reads: the material without its texture.
  @inlinable
  public var surface: Surface {
    Surface(diffuse: diffuse, specular: specular, shininess: shininess)
  }

  /// A material's colours and shininess: plain numbers, so that the fast
  /// engine keeps an array of them and copies one per hit for nothing (a
  /// `Material`, holding a string, is copied through reference counting).
  public struct Surface: Hashable, Sendable {
    public var diffuse: RGB<Scalar>
    public var specular: RGB<Scalar>
    public var shininess: Scalar

    @inlinable
    public init(diffuse: RGB<Scalar>, specular: RGB<Scalar>, shininess: Scalar)
    {
      self.diffuse = diffuse
      self.specular = specular
      self.shininess = shininess
    }

    /// ambient·kd + Σ [kd·max(0, n·l) + ks·max(0, −d·r)^shininess]·light
    /// over the lights, r = 2(n·l)n − l, the specular term where n·l > 0.
    ///
    /// - Parameters:
    ///   - normal: unit normal at the hit.
    ///   - viewDirection: the unit ray direction d (towards the hit).
    ///   - power: highlight^shininess; the course's is the C library's
    ///     `pow`, the compiled engine's `specularPower`.
    @inlinable
    @_specialize(where Scalar == Double)
    public func shade(
      point: Vector3<Scalar>, normal: Vector3<Scalar>,
      viewDirection: Vector3<Scalar>, ambient: RGB<Scalar>,
      lights: [Light<Scalar>], attenuate: Bool,
      power: (Scalar, Scalar) -> Scalar = Scalar.pow
    ) -> RGB<Scalar> {
      var color = ambient * diffuse
      for light in lights {
        let (toLight, lightColor) = light.illumination(
          at: point, attenuate: attenuate)
        let cosine = normal.dot(toLight)
        guard cosine > 0 else { continue }
        var intensity = diffuse * cosine
        let reflected = normal * (2 * cosine) - toLight
        let highlight = -viewDirection.dot(reflected)
        if highlight > 0 {
          intensity += specularTerm(highlight, power: power)
        }
        color += intensity * lightColor
      }
      return color
    }

    /// specular·highlight^shininess, the same bits as computing it in full
    /// (for Double and Float; with the C library's `pow`, or the fast
    /// engine's `specularPower`, which agrees on these cases), with the
    /// power left out where its value is known or cannot show:
    /// - shininess 1: x¹ = x is a double, which the C library's `pow`
    ///   returns (glibc's error is below 0.52 ulp, and a result within that
    ///   of a double is the double; `MaterialSpecularTests` checks 10⁶
    ///   values);
    /// - shininess 0: x⁰ = 1 for every x (C, Annex F);
    /// - a black specular colour (every channel ±0) with 0 ≤ shininess ≤
    ///   1024 and highlight ≤ 1 + 1/16 (from unit vectors it is at most
    ///   1 + 4ε): the power is finite and not negative, below
    ///   (17/16)¹⁰²⁴ < 2⁹⁰, within Float's range, so ±0 times it is that
    ///   same ±0: the product is the specular colour itself.
    /// Most of the course's materials have no specular colour, and its
    /// shininess-1 materials spent a sixth of a supersampled render in
    /// `pow` (docs/PERFORMANCE.md, "Shading").
    ///
    /// In double-double (tests only) `pow` goes through Double, so there
    /// shininess 1 is more accurate than `pow` was.
    @inlinable @inline(__always)
    func specularTerm(
      _ highlight: Scalar, power: (Scalar, Scalar) -> Scalar = Scalar.pow
    ) -> RGB<Scalar> {
      if shininess == 1 { return specular * highlight }
      if shininess == 0 { return specular }
      if specular == .zero && highlight <= 1.0625 && shininess >= 0
        && shininess <= 1024
      {
        return specular
      }
      return specular * power(highlight, shininess)
    }
  }
}
