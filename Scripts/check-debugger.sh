#!/usr/bin/env bash
# The debugger shows the course's variables in the default debug build
# (docs/PORTABILITY.md, "Debugging"): stops gdb at the line of
# `Sphere.intersect` that picks the root, and checks that its locals are
# listed with values (not `<optimized out>`) and that the discriminant
# reads back as a finite number. Installs gdb with apt-get where missing.
# Usage: Scripts/check-debugger.sh [DEBUG_BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${1:-.build/debug/raytrace}
[ -x "$binary" ] || swift build --product raytrace
if ! command -v gdb >/dev/null; then
  apt-get install -y -qq gdb >/dev/null 2>&1 ||
    { apt-get update -qq && apt-get install -y -qq gdb >/dev/null; }
fi
line=$(grep -n 'let t = tMin' Sources/Course/Sphere.swift | cut -d: -f1)
[ -n "$line" ] || { echo "check-debugger: no 'let t = tMin' line in Sphere.swift"; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
timeout 120 gdb -batch -ex "break Sphere.swift:$line" -ex run \
  -ex 'info locals' -ex 'p *(double*)&discriminant' \
  --args "$binary" scenes/spheres.txt -o "$out/out.png" \
  > "$out/gdb.txt" 2>&1 || true
python3 - "$out/gdb.txt" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
if 'hit Breakpoint 1' not in text:
    sys.exit('check-debugger: gdb never stopped in Sphere.intersect:\n' + text[-2000:])
names = ['a', 'b', 'c', 'discriminant', 'q', 'f', 'd']
locals_ = dict(re.findall(r'^(\w+) = (.*)$', text, re.M))
missing = [n for n in names if n not in locals_]
hidden = [n for n in names if 'optimized out' in locals_.get(n, '')]
if missing or hidden:
    sys.exit(f'check-debugger: locals missing {missing}, optimised out {hidden}')
value = re.search(r'^\$1 = (\S+)$', text, re.M)
try:
    number = float(value.group(1))
except (AttributeError, ValueError):
    sys.exit('check-debugger: the discriminant did not read back as a number')
print(f'check-debugger: Sphere.intersect stopped at line with '
      f'{len(locals_)} locals shown; discriminant = {number}')
PY
