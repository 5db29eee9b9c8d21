#!/usr/bin/env bash
# `raytrace report --plot` in a browser: renders two scenes' report (a
# small one: the check is of the picture, not the timings), draws the SVG
# with headless Chromium and checks that its marks are where the CSV's
# numbers put them (Scripts/check-plot.py). Installs Chromium with apt-get
# where it is missing. Usage: Scripts/check-plot.sh [raytrace binary]
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${1:-.build/release/raytrace}
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  apt-get update -qq && apt-get install -y -qq chromium > /dev/null
  browser=$(command -v chromium)
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$binary" report scenes/spheres.txt scenes/stiff/far-sphere-1e6.txt \
  scenes/stiff/grazing-sphere.txt --size 64 64 --runs 3 --rounds 1 \
  --plot "$work/plot.svg" --csv "$work/rows.csv" > /dev/null
size='s/.*<svg [^>]*width="\([0-9]*\)" height="\([0-9]*\)".*/\1 \2/p'
read -r width height < <(sed -n "$size" "$work/plot.svg")
"$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars \
  --force-device-scale-factor=1 --window-size="$width,$height" \
  --screenshot="$work/plot.png" "file://$work/plot.svg" > /dev/null 2>&1
python3 Scripts/check-plot.py "$work/plot.svg" "$work/rows.csv" "$work/plot.png"
