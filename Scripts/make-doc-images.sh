#!/usr/bin/env bash
# Renders every picture in README.md and docs/ from the project's own scenes
# into docs/images/, with the release build. Run from anywhere:
#
#   Scripts/make-doc-images.sh
set -euo pipefail
cd "$(dirname "$0")/.."
swift build -c release
rt=.build/release/raytrace
out=docs/images
mkdir -p "$out"

# The project's scenes, course style, all three outputs.
for scene in spheres spheres-only single-sphere textured; do
  "$rt" "scenes/$scene.txt" --size 400 300 -o "$out/$scene.png" \
    --depth "$out/$scene-depth.png" --normals "$out/$scene-normals.png"
done

# Meshes and transforms, supersampled.
"$rt" scenes/mesh-and-transforms.txt --size 400 300 --samples 16 \
  -o "$out/mesh-and-transforms.png" \
  --normals "$out/mesh-and-transforms-normals.png"

# The original assignment's style, with its own command line.
"$rt" -input scenes/spheres.txt -size 400 300 -output "$out/spheres-mit.png" \
  -normals "$out/spheres-mit-normals.png" \
  -depth 8 18 "$out/spheres-mit-depth.png"

# The planet of radius 10⁹ seen from one unit above, in float: the
# textbook formula and the default.
"$rt" scenes/stiff/planet-1e9.txt --size 400 300 --precision float \
  --intersection naive -o "$out/planet-1e9-naive-float.png"
"$rt" scenes/stiff/planet-1e9.txt --size 400 300 --precision float \
  -o "$out/planet-1e9.png"

# The accuracy report with its default options (a few minutes): error
# against run time as a picture (README.md) and error heatmaps
# (docs/ACCURACY.md).
heatmaps=$(mktemp -d)
trap 'rm -rf "$heatmaps"' EXIT
"$rt" report --heatmaps "$heatmaps" --plot "$out/error-vs-time.svg" >/dev/null
for name in far-sphere-1e6-double-naive far-sphere-1e6-double-stable \
  planet-1e9-float-naive planet-1e9-float-stable; do
  cp "$heatmaps/$name.png" "$out/heatmap-$name.png"
done
echo "make-doc-images: wrote $(ls "$out" | wc -l) images to $out"
