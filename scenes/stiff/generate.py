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


# A unit sphere scene scaled by s: the camera at 3s looking at the origin,
# a sphere of radius s there. Squares of lengths leave the precision's
# range long before the lengths do. Scenes beyond Float's range are double
# only: Float reading refuses their numbers (see DOUBLE_ONLY).
DOUBLE_ONLY = []
for exponent in (10, 20, 30, 100, 200, 300):
    for sign in (1, -1):
        s = 10.0 ** (sign * exponent)
        name = "unit-sphere-1e%d" % (sign * exponent)
        only = exponent > 30
        if only:
            DOUBLE_ONLY.append(name)
        write(name + ".txt", "A unit sphere scene scaled by 1e%d%s." % (sign * exponent,
              " (double only: Float cannot hold its numbers)" if only else ""),
              "r^2 and |p|^2 leave the precision's range unless rescaled.",
              camera((0, 0, 3 * s), (0, 0, -1), (0, 1, 0), 45) + LIGHTS + MATERIALS
              + group(["MaterialIndex 0", sphere((0, 0, 0), s)]))


def triangle(a, b, c):
    f = lambda v: " ".join(repr(float(x)) for x in v)
    return "Triangle { vertex0 %s  vertex1 %s  vertex2 %s }" % (f(a), f(b), f(c))


# A small triangle far away, the field of view just wider than it.
write("far-triangle-1e4.txt", "A unit triangle at distance 1e4, filling the image.",
      "its vertices relative to the eye round to the precision's ulp of 1e4.",
      camera((0.1, 0.2, 1e4), (0, 0, -1), (0, 1, 0), 2 * math.degrees(math.atan(1.2e-4)))
      + LIGHTS + MATERIALS
      + group(["MaterialIndex 0", triangle((-1, -1, 0), (1, -1, 0), (0, 1, 0.5))]))

# A ground triangle 2e6 across seen from one unit above it.
write("ground-triangle.txt", "A ground triangle 2e6 across seen from one unit above it.",
      "the edge functions multiply coordinates of 1e6 by the eye's height of 1.",
      camera((0, 1, 0), (0, -0.2, -1), (0, 1, 0), 60) + LIGHTS + MATERIALS
      + group(["MaterialIndex 2", triangle((-1e6, 0, 1e6), (1e6, 0, 1e6), (0, 0, -1e6)),
               "MaterialIndex 0", sphere((0, 0.5, -4), 0.5)]))

# A triangle seen so close to edge-on that hits run out to t ~ 1e5.
write("grazing-triangle.txt", "A ground triangle at a grazing angle, hits out to t ~ 1e5.",
      "the ray is nearly parallel to the triangle's plane.",
      camera((0, 1, 0), (0, -1e-4, -1), (0, 1, 0), 0.01) + LIGHTS + MATERIALS
      + group(["MaterialIndex 2", triangle((-1e5, 0, 1), (1e5, 0, 1), (0, 0, -2e5))]))


def icosphere(subdivisions):
    """A closed triangle mesh on the unit sphere: an icosahedron whose faces
    are split in four `subdivisions` times, vertices pushed to the sphere."""
    t = (1 + 5 ** 0.5) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    unit = lambda v: tuple(x / math.sqrt(sum(y * y for y in v)) for x in v)
    vertices = [unit(v) for v in vertices]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                vertices.append(unit(tuple((vertices[a][i] + vertices[b][i]) / 2 for i in range(3))))
                middle[key] = len(vertices) - 1
            return middle[key]
        split = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    lines = ["# A unit icosphere (%d faces), written by generate.py." % len(faces)]
    lines += ["v %r %r %r" % v for v in vertices]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in faces]
    return "\n".join(lines) + "\n"


with open("icosphere.obj", "w") as f:
    f.write(icosphere(2))

# The icosphere mesh translated by 1e6 along every axis.
write("mesh-translated-1e6.txt", "A triangle mesh translated by 1e6 along every axis.",
      "vertices relative to the eye cancel in world coordinates.",
      camera((1e6 + 0.3, 1e6 - 0.2, 1e6 + 4), (-0.075, 0.05, -1), (0, 1, 0), 40)
      + LIGHTS + MATERIALS
      + group(["MaterialIndex 1",
               "Transform { Translate 1000000.0 1000000.0 1000000.0 "
               "TriangleMesh { obj_file icosphere.obj } }"]))


# Specks a few of their sizes from the eye (a sphere, a triangle and an
# ellipsoid of size s) beside a planet of radius S 3S away: at one common
# scale the squares of the specks or of the planet leave the precision, so
# each is traced at its own (LengthScale.layers). A wall at x = 0.8s (a
# plane, traced at the planet's scale) hides the ellipsoid and part of the
# planet, so hits are compared across scales. The second is double only.
for small, large in ((1e-20, 1e21), (1e-200, 1e201)):
    s, S = small, large
    name = "specks-and-planet-1e%d" % round(math.log10(large))
    only = large > 1e30
    if only:
        DOUBLE_ONLY.append(name)
    write(name + ".txt", "Specks of size %r beside a planet of radius %r%s." % (s, S,
          " (double only: Float cannot hold its numbers)" if only else ""),
          "no common scale holds the squares of both; each is traced at its own.",
          camera((0, 0, 0), (0, 0, -1), (0, 1, 0), 70) + LIGHTS + MATERIALS
          + group(["MaterialIndex 0", sphere((-1.2 * s, 0.5 * s, -3 * s), 0.5 * s),
                   "MaterialIndex 1", triangle((-0.4 * s, 0.1 * s, -3 * s), (0.4 * s, 0.1 * s, -3 * s),
                                               (0, 0.9 * s, -3 * s)),
                   "MaterialIndex 0",
                   "Transform { Translate %r %r %r Scale %r %r %r Sphere { center 0 0 0 radius 1 } }"
                   % (1.2 * s, 0.5 * s, -3 * s, 0.3 * s, 0.5 * s, 0.3 * s),
                   "MaterialIndex 2", sphere((0.05 * S, -1.2 * S, -3 * S), S),
                   "MaterialIndex 1", plane((1, 0, 0), 0.8 * s)]))
