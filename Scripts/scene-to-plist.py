#!/usr/bin/env python3
"""Writes a text-format scene as the Swift course's property list.

    python3 Scripts/scene-to-plist.py scenes/spheres.txt > scenes/spheres.plist

Covers what the project's scenes use: the camera, point and directional
lights (falloff kept), the background, materials (a texture must be
Textures/NAME.bmp, written as NAME), and groups of spheres, planes,
triangles, meshes (Meshes/NAME.obj, written as NAME) and transforms
(Matrix4f has no plist form and is refused). Each object gets the material
index the text's MaterialIndex gives it; a plane's offset changes sign
(text: n·P = d; plist: n·P + offset = 0). Numbers are copied as written, so
both files hold the same values and render the same bytes.
"""
import plistlib
import re
import sys


def tokens(text):
    text = re.sub(r"#[^\n]*", " ", text)
    return re.findall(r"[{}]|[^\s{}]+", text)


class Reader:
    def __init__(self, words):
        self.words = words
        self.at = 0

    def next(self):
        word = self.words[self.at]
        self.at += 1
        return word

    def expect(self, word):
        found = self.next()
        if found != word:
            sys.exit("expected %r, found %r" % (word, found))

    def numbers(self, count):
        return " ".join(self.next() for _ in range(count))

    def fields(self, counts):
        """A { name value … } block: counts maps each field to its arity
        (0: a word)."""
        self.expect("{")
        values = {}
        while True:
            word = self.next()
            if word == "}":
                return values
            if word not in counts:
                sys.exit("unsupported field %r" % word)
            arity = counts[word]
            values[word] = self.next() if arity == 0 else self.numbers(arity)


def negated(number):
    return number[1:] if number.startswith("-") else "-" + number


def name_in(path, folder, extension):
    match = re.fullmatch(r"%s/(.+)\.%s" % (folder, extension), path)
    if not match:
        sys.exit("%r must be %s/NAME.%s to have a plist form" %
                 (path, folder, extension))
    return match.group(1)


def read_object(reader, word, material):
    if word == "Sphere":
        f = reader.fields({"center": 3, "radius": 1})
        return {"type": "Sphere", "materialIndex": str(material),
                "center": f["center"], "radius": f["radius"]}
    if word == "Plane":
        f = reader.fields({"normal": 3, "offset": 1})
        return {"type": "Plane", "materialIndex": str(material),
                "normal": f["normal"], "offset": negated(f["offset"])}
    if word == "Triangle":
        f = reader.fields({"vertex0": 3, "vertex1": 3, "vertex2": 3})
        return dict(type="Triangle", materialIndex=str(material), **f)
    if word == "TriangleMesh":
        f = reader.fields({"obj_file": 0})
        return {"type": "TriangleMesh", "materialIndex": str(material),
                "objFile": name_in(f["obj_file"], "Meshes", "obj")}
    if word == "Group":
        return {"type": "Group", "Group": read_group(reader, material)}
    if word == "Transform":
        reader.expect("{")
        operations = []
        arity = {"Translate": 3, "Scale": 3, "UniformScale": 1,
                 "XRotate": 1, "YRotate": 1, "ZRotate": 1, "Rotate": 4}
        while True:
            word = reader.next()
            if word in arity:
                name = word[0].lower() + word[1:]
                operations.append(name + " " + reader.numbers(arity[word]))
                continue
            child = read_object(reader, word, material)
            reader.expect("}")
            child.pop("materialIndex", None)
            return {"type": "Transform", "materialIndex": str(material),
                    "transforms": operations, "transformed": child}
    sys.exit("unsupported object %r" % word)


def read_group(reader, material):
    reader.expect("{")
    reader.expect("numObjects")
    reader.next()
    objects = []
    while True:
        word = reader.next()
        if word == "}":
            return objects
        if word == "MaterialIndex":
            material = int(reader.next())
            continue
        objects.append(read_object(reader, word, material))


def convert(text):
    reader = Reader(tokens(text))
    scene = {}
    while reader.at < len(reader.words):
        block = reader.next()
        if block == "PerspectiveCamera":
            f = reader.fields(
                {"center": 3, "direction": 3, "up": 3, "angle": 1})
            scene["Camera"] = dict(type="PerspectiveCamera", **f)
        elif block == "Lights":
            reader.expect("{")
            reader.expect("numLights")
            reader.next()
            lights = []
            while (word := reader.next()) != "}":
                if word == "PointLight":
                    f = reader.fields(
                        {"position": 3, "color": 3, "falloff": 1})
                else:
                    f = reader.fields({"direction": 3, "color": 3})
                lights.append(dict(type=word, **f))
            scene["Lights"] = lights
        elif block == "Background":
            scene["Background"] = reader.fields(
                {"color": 3, "ambientLight": 3})
        elif block == "Materials":
            reader.expect("{")
            reader.expect("numMaterials")
            reader.next()
            materials = []
            while (word := reader.next()) != "}":
                f = reader.fields({"diffuseColor": 3, "specularColor": 3,
                                   "shininess": 1, "texture": 0})
                if "texture" in f:
                    f["texture"] = name_in(f["texture"], "Textures", "bmp")
                materials.append(dict(type="PhongMaterial", **f))
            scene["Materials"] = materials
        elif block == "Group":
            scene["Group"] = read_group(reader, 0)
        else:
            sys.exit("unsupported block %r" % block)
    return plistlib.dumps(scene, fmt=plistlib.FMT_XML, sort_keys=False)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        sys.stdout.buffer.write(convert(f.read()))
