#!/usr/bin/env bash
# Every week's handout builds, and its tests say what is left to write
# (docs/TEACHING.md). For each week N marked in Sources/Course, makes the
# handout (Scripts/make-handout.sh N), builds the course's closure from it
# and runs the course's tests one week at a time, each week in its own
# `swift test` so that a crash (the fatalError of a body left to write)
# ends only that week's run:
#   - every earlier week's tests pass;
#   - week N's tests fail, on week N's own fatalError (a crash naming a
#     later week means a test of week N needs code of a later week).
# Then the model answer itself: every week's tests pass.
#
# Fast: one scratch package (Scripts/handouts/Package.swift: RealModule,
# Geometry, SceneDescription, Course, CourseTests) into which each week's
# sources are copied, only the files that changed, so that a week
# rebuilds the course target and its tests, not the package. It lives in
# .build/handouts (RAYTRACE_HANDOUT_SCRATCH to move it).
# Usage: Scripts/check-handouts.sh
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
scratch=${RAYTRACE_HANDOUT_SCRATCH:-$root/.build/handouts}
package=$scratch/package
mkdir -p "$package"
start=$SECONDS

# Copies folder $1 to $2, writing only the files whose bytes differ (so
# that the build sees unchanged files as unchanged) and removing the rest.
sync_folder() {
  python3 - "$1" "$2" <<'PY'
import filecmp, os, shutil, sys
source, target = sys.argv[1:3]
wanted = set()
for folder, _, names in os.walk(source):
    for name in names:
        path = os.path.relpath(os.path.join(folder, name), source)
        wanted.add(path)
        to = os.path.join(target, path)
        if os.path.exists(to) and filecmp.cmp(
                os.path.join(source, path), to, shallow=False):
            continue
        os.makedirs(os.path.dirname(to), exist_ok=True)
        shutil.copyfile(os.path.join(source, path), to)
for folder, _, names in os.walk(target):
    for name in names:
        path = os.path.relpath(os.path.join(folder, name), target)
        if path not in wanted:
            os.remove(os.path.join(target, path))
PY
}

# The course's closure of the tree at $1 into the scratch package.
load() {
  for folder in Sources/RealModule Sources/Geometry Sources/SceneDescription \
    Sources/Course Tests/CourseTests; do
    sync_folder "$1/$folder" "$package/$folder"
  done
  cmp -s Scripts/handouts/Package.swift "$package/Package.swift" ||
    cp Scripts/handouts/Package.swift "$package/Package.swift"
}

failures=0
fail() {
  echo "check-handouts: FAIL: $*"
  failures=$((failures + 1))
}

# Builds the scratch package; fails the check on any error, or on a
# warning in the course's code or its tests (a handout must build clean).
build() {
  local log=$scratch/build.log
  if ! swift build --package-path "$package" --build-tests >"$log" 2>&1; then
    tail -n 40 "$log"
    fail "$1 does not build"
    return 1
  fi
  if grep -E '(Sources/Course|Tests/CourseTests)/.*: warning:' "$log"; then
    fail "$1 builds with warnings in the course's code or tests"
  fi
}

# Runs week $1's tests; prints "passes", "fails", "ran no test" or "stops
# at week K's fatalError" (a body left to write crashed the run), and
# keeps the output in $scratch/week$1.log.
run_week() {
  local log=$scratch/week$1.log
  if swift test --package-path "$package" --skip-build \
    --filter "CourseTests\\.Week$1_" >"$log" 2>&1; then
    if grep -qE "Executed [1-9][0-9]* tests?, with 0 failures" "$log"; then
      echo passes
    else
      echo "ran no test"
    fi
  elif grep -qE 'Fatal error: Week [0-9]+ \(' "$log"; then
    echo "stops at week $(grep -oE 'Fatal error: Week [0-9]+' "$log" |
      head -n 1 | grep -oE '[0-9]+$')'s fatalError"
  else
    echo fails
  fi
}

# The scratch manifest copies Package.swift's settings for the course's
# closure: any drift fails the check (compared through dump-package).
load "$root"
python3 - <(swift package dump-package) \
  <(swift package --package-path "$package" dump-package) <<'PY' ||
import json, sys
real, scratch = (json.load(open(path)) for path in sys.argv[1:3])
def settings(manifest):
    return {t["name"]: t.get("settings", []) for t in manifest["targets"]}
real, scratch = settings(real), settings(scratch)
differ = [name for name in ("Geometry", "SceneDescription", "Course",
                            "CourseTests") if real.get(name) != scratch.get(name)]
if differ:
    sys.exit("settings differ from Package.swift's for " + ", ".join(differ))
PY
  fail "Scripts/handouts/Package.swift is out of step with Package.swift"

weeks=$(python3 Scripts/handout.py list . | cut -f1 | sort -n | uniq)
[ -n "$weeks" ] || { echo "check-handouts: no week is marked"; exit 1; }
for week in $weeks; do
  if ! grep -qE "class Week${week}_" -r Tests/CourseTests; then
    fail "week $week has no test class named Week${week}_…"
  fi
done
for week in $(grep -rhoE 'class Week[0-9]+_' Tests/CourseTests |
  grep -oE '[0-9]+' | sort -n | uniq); do
  echo "$weeks" | grep -qx "$week" ||
    fail "Week${week}_ tests, but no method of Sources/Course is marked" \
      "for week $week"
done

for week in $weeks; do
  handout=$scratch/handout
  rm -rf "$handout"
  bash Scripts/make-handout.sh "$week" "$handout" >"$scratch/make.log"
  load "$handout"
  rm -rf "$handout"
  build "the handout of week $week" || continue
  line="week $week's handout (at $((SECONDS - start)) s):"
  problems=()
  for earlier in $weeks; do
    [ "$earlier" -lt "$week" ] || break
    result=$(run_week "$earlier")
    line+=" week $earlier $result;"
    [ "$result" = passes ] || problems+=(
      "week $earlier's tests: $result ($scratch/week$earlier.log)")
  done
  result=$(run_week "$week")
  line+=" week $week $result"
  case $result in
    "stops at week $week's fatalError") ;;
    stops*) problems+=(
      "week $week's tests need a later week's code: they $result") ;;
    *) problems+=("week $week's tests: $result, not its fatalError") ;;
  esac
  echo "$line"
  for problem in ${problems[@]+"${problems[@]}"}; do
    fail "week $week's handout: $problem"
  done
done

load "$root"
if build "the model answer"; then
  line="the model answer (at $((SECONDS - start)) s):"
  separator=""
  for week in $weeks; do
    result=$(run_week "$week")
    line+="$separator week $week $result"
    separator=";"
    [ "$result" = passes ] ||
      fail "the model answer: week $week's tests: $result" \
        "($scratch/week$week.log)"
  done
  echo "$line"
fi

echo "check-handouts: $((SECONDS - start)) s, $failures failures"
[ "$failures" = 0 ]
