"""Writes the stiff and extreme suite: scenes where the textbook sphere and
plane formulas lose digits. Run from this folder: python3 generate.py"""
import math

HEADER = """# {title}
# Written by generate.py; {why}
"""
MATERIALS = """Materials {
    numMaterials 3
    PhongMaterial { diffuseColor 0.8 0.3 0.25  specularColor 0.6 0.6 0.6  shininess 20 }
    PhongMaterial { diffuseColor 0.3 0.6 0.85 }
    PhongMaterial { diffuseColor 0.7 0.7 0.6 }
}
"""
LIGHTS = """Lights {
    numLights 1
    DirectionalLight { direction -0.3 -1 -0.5  color 0.9 0.9 0.9 }
}
Background { color 0.05 0.05 0.1  ambientLight 0.15 0.15 0.15 }
"""


def camera(center, direction, up, angle):
    f = lambda v: " ".join(repr(float(x)) for x in v)
    return ("PerspectiveCamera {\n    center %s\n    direction %s\n    up %s\n    angle %r\n}\n"
            % (f(center), f(direction), f(up), angle))


def group(objects):
    body = "\n".join("    " + o for o in objects)
    return "Group {\n    numObjects %d\n%s\n}\n" % (sum(1 for o in objects if not o.startswith("MaterialIndex")), body)


def sphere(c, r):
    return "Sphere { center %r %r %r  radius %r }" % (float(c[0]), float(c[1]), float(c[2]), float(r))


def plane(n, d):
    return "Plane { normal %r %r %r  offset %r }" % (float(n[0]), float(n[1]), float(n[2]), float(d))


def write(name, title, why, text):
    with open(name, "w") as f:
        f.write(HEADER.format(title=title, why=why) + text)


# A unit sphere L away, the field of view just wider than the sphere so that
# it fills the image: b^2 - 4ac cancels as (L/r)^2.
for exponent in (2, 4, 6, 8):
    ratio = 10.0 ** exponent
    angle = 2 * math.degrees(math.asin(1 / ratio)) * 1.15
    write("far-sphere-1e%d.txt" % exponent, "A unit sphere at distance 1e%d, filling the image." % exponent,
          "the discriminant cancels as (L/r)^2.",
          camera((0.3, -0.2, ratio), (0, 0, -1), (0, 1, 0), angle) + LIGHTS + MATERIALS
          + group(["MaterialIndex 0", sphere((0.3, -0.2, 0), 1)]))

# A planet of radius R, the camera one unit above its surface looking at the
# horizon: c = |f|^2 - r^2 cancels as R.
for exponent in (4, 6, 9):
    radius = 10.0 ** exponent
    write("planet-1e%d.txt" % exponent, "A planet of radius 1e%d seen from one unit above its surface." % exponent,
          "c = |o - centre|^2 - r^2 cancels.",
          camera((0, 1, 0), (0, -0.2, -1), (0, 1, 0), 60) + LIGHTS + MATERIALS
          + group(["MaterialIndex 2", sphere((0, -radius, 0), radius),
                   "MaterialIndex 0", sphere((0, 0.5, -4), 0.5)]))

# Rays grazing a sphere's silhouette: the discriminant is near zero across
# the whole narrow image.
write("grazing-sphere.txt", "Rays grazing the limb of a unit sphere.",
      "the discriminant is near zero in every pixel.",
      camera((1.0, 0, 10), (0, 0, -1), (0, 1, 0), 0.2) + LIGHTS + MATERIALS
      + group(["MaterialIndex 0", sphere((0, 0, 0), 1)]))

# A ground plane seen so close to edge-on that hits run out to t ~ 1e6.
write("grazing-plane.txt", "A ground plane at a grazing angle, hits out to t ~ 1e6.",
      "n.d is tiny and t = (d - n.o)/(n.d) is large.",
      camera((0, 1, 0), (0, -1e-6, -1), (0, 1, 0), 0.01) + LIGHTS + MATERIALS
      + group(["MaterialIndex 2", plane((0, 1, 0), 0)]))

write("camera-inside-sphere.txt", "The camera inside a large sphere, a small sphere in front.",
      "every ray must hit the far side from inside.",
      camera((0, 0, 0), (0, 0, -1), (0, 1, 0), 70) + LIGHTS + MATERIALS
      + group(["MaterialIndex 2", sphere((0.5, 0.3, -0.2), 6), "MaterialIndex 0", sphere((0, 0, -3), 0.8)]))

write("sphere-behind-camera.txt", "A sphere behind the camera and one in front.",
      "roots behind the eye must be rejected.",
      camera((0, 0, 5), (0, 0, -1), (0, 1, 0), 40) + LIGHTS + MATERIALS
      + group(["MaterialIndex 0", sphere((0, 0, 9), 2), "MaterialIndex 1", sphere((0, 0, 0), 1)]))

write("camera-on-plane.txt", "The camera exactly on the ground plane, looking along it.",
      "the eye's distance to the plane is zero: no ray may hit it at t > 0.",
      camera((0, 0, 5), (0, -0.1, -1), (0, 1, 0), 50) + LIGHTS + MATERIALS
      + group(["MaterialIndex 2", plane((0, 1, 0), 0), "MaterialIndex 0", sphere((0, -0.8, -2), 0.6)]))

# With an odd image height the middle row's rays are exactly parallel to the
# plane (course style, pixel centres): they must miss it.
write("parallel-plane.txt", "Rays exactly parallel to a plane in the middle row.",
      "n.d = 0 exactly: those rays miss the plane.",
      camera((0, 1, 0), (0, 0, -1), (0, 1, 0), 60) + LIGHTS + MATERIALS
      + group(["MaterialIndex 2", plane((0, 1, 0), 0), "MaterialIndex 0", sphere((0, 1, -6), 1)]))


# The project's course-like scene, translated far from the origin and
# scaled down: only the relative positions matter, so depth must follow.
def course_like(offset, scale):
    o = lambda v: tuple(offset[i] + scale * v[i] for i in range(3))
    spheres = [((0, 0, 0), 1.2, 0), ((-2.6, -0.4, 1), 0.8, 1), ((2.5, -0.5, 1.5), 0.7, 1),
               ((-1.4, 0.2, -3), 1.4, 0), ((2.2, 0.6, -2.5), 1.8, 1)]
    objects = []
    for c, r, m in spheres:
        objects += ["MaterialIndex %d" % m, sphere(o(c), scale * r)]
    # n.P = d for the plane y = -1.2 moved and scaled.
    objects += ["MaterialIndex 2", plane((0, 1, 0), offset[1] + scale * -1.2)]
    return (camera(o((0, 1.5, 12)), (0, -0.12, -1), (0, 1, 0), 32) + LIGHTS + MATERIALS + group(objects))


write("translated-far.txt", "The course-like scene translated by 1e6 along every axis.",
      "o - centre cancels in world coordinates.", course_like((1e6, 1e6, 1e6), 1))
write("scaled-small.txt", "The course-like scene scaled by 1e-6.",
      "every length is tiny; nothing may underflow.", course_like((0, 0, 0), 1e-6))
