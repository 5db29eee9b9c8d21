#!/usr/bin/env python3
"""The layer check: nothing below the pipeline names what sits above it,
and every file imports only what its target declares.

    python3 Scripts/check-layers.py              # check the package
    python3 Scripts/check-layers.py --self-test  # and show it catches both

For each target of Package.swift (as `swift package dump-package` reads
it), every `import` of every file in Sources/TARGET or Tests/TARGET must
name a dependency the target declares, or a module of the platform.
Below the pipeline (docs/ENGINES.md draws the layers), the targets'
code and comments must not name an engine that is not theirs, a
command-line option, or the measurements and pipeline above them.
Prints one line per problem, FILE:LINE: error: ..., and exits 1 if any.
"""
import json
import os
import re
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))

# Modules of the toolchain and the platform, which no target declares.
SYSTEM = {
    "Foundation", "FoundationEssentials", "Dispatch", "XCTest", "Testing",
    "Glibc", "Darwin", "Musl", "Android", "WinSDK", "os", "Synchronization",
}

WORDS = {
    "the course engine": r"(?i:course engine)|\bCourseEngine\b",
    "the fast engine": r"(?i:fast engine)|\bFastEngine\b|\bFastScene\b|"
    r"\bFastOptions\b",
    "a command-line option": r"(?<![\w-])--[a-z][a-z0-9-]+",
    "what sits above the engines": r"(?i:\bbench(mark)?s?\b|raytrace report|"
    r"\bpipeline\b|command line)|\bMeasurement\b",
}

# What each target below the pipeline must not name. The course target
# is the course engine; the fast engine's targets (its kernels beneath it)
# are the fast engine.
BELOW = {
    "Geometry": list(WORDS),
    "SceneDescription": list(WORDS),
    "ExactArithmetic": list(WORDS),
    "PlatformSupport": list(WORDS),
    "SceneIO": list(WORDS),
    "Course": ["the fast engine", "a command-line option",
               "what sits above the engines"],
    "FastKernels": ["the course engine", "a command-line option",
                    "what sits above the engines"],
    "FastEngine": ["the course engine", "a command-line option",
                   "what sits above the engines"],
}

IMPORT = re.compile(
    r"^\s*(?:@[\w]+(?:\([^)]*\))?\s+)*import\s+(?:(?:struct|class|enum|"
    r"protocol|func|var|let|typealias)\s+)?([A-Za-z_][\w]*)")


def targets():
    """Each target's name, folder and declared dependencies."""
    dump = subprocess.run(
        ["swift", "package", "dump-package"], cwd=ROOT, check=True,
        capture_output=True, text=True).stdout
    found = {}
    for target in json.loads(dump)["targets"]:
        names = set()
        for dependency in target["dependencies"]:
            (kind, value), = dependency.items()
            names.add(value[0])
        folder = target.get("path") or os.path.join(
            "Tests" if target["type"] == "test" else "Sources",
            target["name"])
        found[target["name"]] = (folder, names)
    return found


def sources(folder):
    """The Swift files under `folder`, as {path: text}."""
    files = {}
    for base, _, names in os.walk(os.path.join(ROOT, folder)):
        for name in sorted(names):
            if name.endswith(".swift"):
                path = os.path.join(base, name)
                with open(path, encoding="utf-8") as file:
                    files[os.path.relpath(path, ROOT)] = file.read()
    return files


def check(layout, files):
    """The problems of `files` ({path: text}) in `layout`."""
    problems = []
    for name, (folder, dependencies) in sorted(layout.items()):
        prefix = folder.rstrip("/") + "/"
        allowed = dependencies | SYSTEM | {name}
        words = [(what, re.compile(WORDS[what]))
                 for what in BELOW.get(name, [])]
        for path, text in sorted(files.items()):
            if not path.startswith(prefix):
                continue
            for number, line in enumerate(text.splitlines(), 1):
                imported = IMPORT.match(line)
                if imported and imported.group(1) not in allowed:
                    problems.append(
                        f"{path}:{number}: error: imports "
                        f"{imported.group(1)}, which Package.swift does not "
                        f"declare for {name}")
                for what, pattern in words:
                    if pattern.search(line):
                        problems.append(
                            f"{path}:{number}: error: {name} is below the "
                            f"pipeline and names {what}: {line.strip()}")
    return problems


def main():
    layout = targets()
    files = {}
    for folder, _ in layout.values():
        files.update(sources(folder))
    problems = check(layout, files)
    for problem in problems:
        print(problem)
    if "--self-test" in sys.argv[1:]:
        # A planted import and a planted word must each be caught.
        planted = {
            "import Course": ("Sources/SceneIO/Planted.swift",
                              "import Course\n"),
            "the words 'course engine'": (
                "Sources/ExactArithmetic/Planted.swift",
                "/// as the course engine computes it\n"),
        }
        for what, (path, text) in planted.items():
            caught = check(layout, dict(files, **{path: text}))
            if len(caught) <= len(problems):
                print(f"self-test: error: a planted {what} in {path} "
                      "was not caught")
                return 1
            print(f"self-test: a planted {what} in {path} is caught")
    if problems:
        return 1
    print(f"layers: {len(files)} files, every import declared, "
          "nothing below the pipeline names what sits above it")
    return 0


if __name__ == "__main__":
    sys.exit(main())
