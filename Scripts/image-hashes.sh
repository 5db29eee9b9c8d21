#!/usr/bin/env bash
# Renders every project scene, the stiff suite and (when ../shared is beside
# the checkout) the course's scenes, with both engines, in each precision, method, style and
# sampling, and prints one line per image: its SHA-256 and how it was made.
# The shaded image is written as PPM, so that the hash is of the pixels and
# not of how a PNG encoder happened to compress them.
# Compare the output of two builds to show a change leaves images bit for bit:
#   Scripts/image-hashes.sh .build/release/raytrace > before.txt
#   ... change, rebuild ...
#   Scripts/image-hashes.sh .build/release/raytrace | diff before.txt -
set -euo pipefail
binary=${1:-.build/release/raytrace}
cd "$(dirname "$0")/.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

scenes=(scenes/*.txt scenes/*.plist scenes/stiff/*.txt)
for reference in ../shared/reference/mit/*.txt \
  ../shared/reference/course/*.txt \
  ../shared/reference/swift-course/Scenes/*.plist; do
  [ -f "$reference" ] && scenes+=("$reference")
done

render() {
  local label=$1; shift
  "$binary" "$@" -o "$out/s.ppm" --depth "$out/d.pfm" \
    --normals "$out/n.pfm" 2>/dev/null || { echo "failed  $label"; return; }
  # One hash per output, so that a diff says which changed (a change may
  # move depth values in their last bits and leave the images alone).
  local h=()
  for file in s.ppm d.pfm n.pfm; do
    h+=("$(sha256sum < "$out/$file" | cut -c1-12)")
  done
  echo "shaded ${h[0]} depth ${h[1]} normals ${h[2]}  $label"
}

for scene in "${scenes[@]}"; do
  for precision in double float; do
    for method in stable naive; do
      render "$scene $precision $method" "$scene" --size 96 80 \
        --engine fast --precision "$precision" --intersection "$method"
    done
  done
  # Both engines in each style and sampling (the course engine computes in
  # Double by its own method only).
  for engine in fast course; do
    render "$scene $engine mit" "$scene" --size 96 80 --style mit \
      --engine $engine
    render "$scene $engine 16 samples" "$scene" --size 64 48 --samples 16 \
      --engine $engine
    render "$scene $engine 300x300" "$scene" --size 300 300 --engine $engine
  done
done
