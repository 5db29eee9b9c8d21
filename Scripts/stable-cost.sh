#!/usr/bin/env bash
# The stable method's render time against naive's, per stiff scene and
# precision: for each, the minimum over five alternating rounds of the
# median of 21 renders (400×400, one thread, depth and normals), which is
# steadier on a shared machine than one median. Prints
#   scene precision naive-seconds stable-seconds stable/naive
# Usage: Scripts/stable-cost.sh [binary] [scene ...]
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${1:-.build/release/raytrace}
shift || true
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(scenes/stiff/*.txt)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() {
  "$binary" "$1" --size 400 400 --threads 1 --precision "$2" \
    --intersection "$3" --depth "$out/d.pfm" --normals "$out/n.pfm" \
    --repeat 21 --stats 2>&1 | awk '/^render:/ {print $2}'
}

for scene in "${scenes[@]}"; do
  for precision in float double; do
    naive="" stable=""
    for _ in 1 2 3 4 5; do
      n=$(median "$scene" "$precision" naive) || true
      s=$(median "$scene" "$precision" stable) || true
      [ -z "$n" ] || [ -z "$s" ] && continue 2  # not renderable in this precision
      naive=$(printf '%s\n%s\n' "${naive:-$n}" "$n" | sort -g | head -1)
      stable=$(printf '%s\n%s\n' "${stable:-$s}" "$s" | sort -g | head -1)
    done
    echo "$(basename "$scene" .txt) $precision $naive $stable" \
      "$(awk "BEGIN {printf \"%.3f\", $stable / $naive}")"
  done
done
