#!/usr/bin/env bash
# Checks that raytrace built against the real packages behaves as the build
# with the stand-ins does (docs/PORTABILITY.md, "Packages"):
#
#   Scripts/check-real-packages.sh ARGPARSER_CHECKOUT NUMERICS_CHECKOUT
#
# 1. builds the stand-ins' raytrace (swift build -c release, .build/);
# 2. builds raytrace against the two local checkouts of
#    swift-argument-parser and swift-numerics, in release mode, in its own
#    build folder (--scratch-path .build/real-packages), and runs the test
#    suite there (CHECK_SKIP_TESTS=1 skips it);
# 3. runs each command line below with both binaries, from the package
#    root, and compares exit codes, standard output, standard error and the
#    files written (by bytes). OUT in a command line is a fresh folder per
#    binary and case; its path reads OUT in the outputs compared.
#
# Prints every difference and exits 1 on any, 64 for a usage error.
# Without a terminal, both print help 80 columns wide: COLUMNS and LINES
# are unset for the runs (the real package would wrap to them).
set -euo pipefail

if [ $# -ne 2 ] || [ ! -d "$1" ] || [ ! -d "$2" ]; then
  echo "usage: Scripts/check-real-packages.sh ARGPARSER_CHECKOUT" \
    "NUMERICS_CHECKOUT (two folders)" >&2
  exit 64
fi
parser=$(cd "$1" && pwd)
numerics=$(cd "$2" && pwd)
cd "$(dirname "$0")/.."
scratch=.build/real-packages

# Named as given (a copy inside this work tree would describe this
# repository's commit).
for checkout in "$parser" "$numerics"; do
  version=$(git -C "$checkout" describe --tags --always 2>/dev/null ||
    echo "not a git checkout")
  echo "== $checkout ($version)"
done

# Each checkout is built from a copy of its own beside the scratch folder,
# so that a read-only checkout (../shared/packages) is never written to,
# with the symbolic links that a plain copy of a repository's tree turns
# into files restored: a file with no extension whose whole content is a
# relative path to something beside it (swift-argument-parser's
# Plugins/GenerateManual/GenerateCommon, a link to ../GenerateCommon).
copy_checkout() {
  local from=$1 to
  to=$PWD/$scratch-checkouts/$(basename "$from")
  rm -rf "$to"
  mkdir -p "$(dirname "$to")"
  cp -R "$from" "$to"
  chmod -R u+w "$to"
  local file target
  while IFS= read -r -d '' file; do
    target=$(cat "$file")
    case $target in
    */* | ..) ;;
    *) continue ;;
    esac
    if [ -e "$(dirname "$file")/$target" ]; then
      rm "$file"
      ln -s "$target" "$file"
    fi
  done < <(find "$to" -type f -size -256c ! -name '*.*' -print0)
  echo "$to"
}
parser=$(copy_checkout "$parser")
numerics=$(copy_checkout "$numerics")

# The stand-in build must not see the switch, whatever the caller set.
unset RAYTRACE_PACKAGES RAYTRACE_ARGUMENT_PARSER_PATH RAYTRACE_NUMERICS_PATH
real() {
  RAYTRACE_PACKAGES="$parser:$numerics" "$@" --scratch-path "$scratch"
}

echo "== stand-ins: swift build -c release"
swift build -c release
standin_bin=$(swift build -c release --show-bin-path)/raytrace

echo "== real packages: swift build -c release --scratch-path $scratch"
real swift build -c release
real_bin=$(real swift build -c release --show-bin-path)/raytrace

if [ "${CHECK_SKIP_TESTS:-0}" != 1 ]; then
  echo "== real packages: swift test --scratch-path $scratch"
  real swift test
fi

# One command line a line; words split at spaces, OUT for the output folder.
# Left out on purpose: report and bench runs (their timings differ from
# run to run) and the stand-in's deliberate differences (docs/PORTABILITY.md,
# "Packages"): completion scripts, help wrapped to the terminal, and an
# unknown single-dash word such as `-outptu`, which the real package splits
# into short options (`-o` then takes the next value; `-u` is unknown).
cases=$(
  cat <<'EOF'
--help
-h
help
help render
help report
help bench
render --help
report --help
bench -h
scenes/spheres.txt --help
scenes/spheres.txt -o OUT/a.png --help
scenes/spheres.txt --outptu OUT/a.png --help
--help render
--help -1
scenes/spheres.txt
render
scenes/spheres.txt --outptu OUT/a.png
scenes/spheres.txt -o OUT/a.png --png-levl 3
scenes/spheres.txt -o OUT/a.png -z
scenes/spheres.txt -o OUT/a.png --version
scenes/spheres.txt -o OUT/a.png extra
scenes/spheres.txt -o OUT/a.png extra1 extra2
scenes/spheres.txt extra --outptu
scenes/spheres.txt -o
scenes/spheres.txt -o OUT/a.jpg
scenes/spheres.txt -o OUT/a.png --output OUT/a.png
scenes/spheres.txt -o OUT/a.png --size 10
scenes/spheres.txt -o OUT/a.png --size x 10
scenes/spheres.txt -o OUT/a.png --size 0 10
scenes/spheres.txt -o OUT/a.png --size -5 10
scenes/spheres.txt -o OUT/a.png --precision quad
scenes/spheres.txt -o OUT/a.png --samples 3
scenes/spheres.txt -o OUT/a.png --threads 0
scenes/spheres.txt -o OUT/a.png --threads -2
scenes/spheres.txt -o OUT/a.png --png-level 12
scenes/spheres.txt -o OUT/a.png --engine course --precision float
scenes/spheres.txt --size 40 30 --depth OUT/d.png --repeat -1
scenes/spheres.txt --size 40 30 --depth OUT/d.png --repeat
scenes/spheres.txt --size 40 30 --depth OUT/d.png --repeat x
scenes/spheres.txt --size 40 30 --depth OUT/d.png --repeat 2
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range -1 20
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range -10 -1
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range 2 -1
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range -.5 9.5
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range=-1 20
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range -1
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range -1 x
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range
scenes/spheres.txt --size 40 30 --depth-range 1 --depth OUT/d.png
scenes/spheres.txt --size 40 30 --depth OUT/d.png --depth-range -inf 2
-input scenes/spheres.txt -size 64 48 -output OUT/a.png -normals OUT/n.png -depth 8 18 OUT/d.png
-input scenes/spheres.txt -size 64 48 -depth -1 20 OUT/d.png -output OUT/a.png
-input scenes/spheres.txt -size 64 48 -depth -20 -1 OUT/d.png
-input scenes/spheres.txt -size 64 48 -depth 5 -2 OUT/d.png
-input scenes/spheres.txt -size 64 48 -depth -1 OUT/d.png
-input scenes/spheres.txt -size 64 48 -depth
-input scenes/spheres.txt -size 64 48 -jitter -filter tent -output OUT/a.png
scenes/spheres.txt -input scenes/spheres.txt -o OUT/a.png
scenes/spheres.txt --size 32 24 -o OUT/a.png --depth OUT/d.pfm --normals OUT/n.npy
scenes/spheres.txt --size 32 24 -o OUT/a.ppm --depth OUT/d.npy --normals OUT/n.pfm --precision float
scenes/spheres.txt --size 32 24 -o OUT/a.png --samples 4 --filter tent --style mit
scenes/spheres.txt --size 32 24 -o OUT/a.png --engine course --intersection naive
scenes/mesh-and-transforms.txt --size 32 24 -o OUT/a.png --normals OUT/n.png
scenes/textured.plist --size 32 24 -o OUT/a.png --png-level 0
scenes/does-not-exist.txt -o OUT/a.png
render scenes/spheres.txt --size 16 16 -o OUT/a.png
render -- -x
-- -x
report --frob
report --size 1
report --runs 0 scenes/spheres.txt
report --threads 0
bench --runs 0
bench --frob
bench extra
EOF
)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run BINARY FOLDER ARGUMENT...: exit code, stdout and stderr in FOLDER, the
# files written in FOLDER/out.
run() {
  local binary=$1 folder=$2
  shift 2
  mkdir -p "$folder/out"
  local arguments=() word
  for word in "$@"; do
    arguments+=("${word//OUT/$folder/out}")
  done
  local status=0
  env -u COLUMNS -u LINES "$binary" "${arguments[@]}" \
    >"$folder/stdout" 2>"$folder/stderr" </dev/null || status=$?
  echo "$status" >"$folder/status"
  # The folder's path reads OUT, as in the command line.
  sed -i "s|$folder/out|OUT|g" "$folder/stdout" "$folder/stderr"
}

differences=0
count=0
while IFS= read -r line; do
  [ -n "$line" ] || continue
  count=$((count + 1))
  read -ra words <<<"$line"
  a=$work/$count/stand-in
  b=$work/$count/real
  run "$standin_bin" "$a" "${words[@]}"
  run "$real_bin" "$b" "${words[@]}"
  report=""
  for part in status stdout stderr; do
    if ! cmp -s "$a/$part" "$b/$part"; then
      report+="  $part differs (< stand-in, > real packages):"$'\n'
      report+=$(diff "$a/$part" "$b/$part" | sed 's/^/    /' | head -40 ||
        true)
      report+=$'\n'
    fi
  done
  if ! diff -r -q "$a/out" "$b/out" >/dev/null; then
    report+="  files differ:"$'\n'
    report+=$(diff -r -q "$a/out" "$b/out" | sed "s|$work/$count/||g;
      s/^/    /" || true)$'\n'
  fi
  status=$(cat "$a/status")
  files=$(find "$a/out" -type f | wc -l)
  if [ -n "$report" ]; then
    differences=$((differences + 1))
    echo "DIFFERS raytrace $line"
    printf '%s' "$report"
  else
    echo "same    raytrace $line  (exit $status, $files files)"
  fi
done <<<"$cases"

if [ "$differences" -gt 0 ]; then
  echo "== $differences of $count command lines differ" >&2
  exit 1
fi
echo "== all $count command lines agree"
