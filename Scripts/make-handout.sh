#!/usr/bin/env bash
# The student's starting point for week WEEK of the course, made from the
# model answer (docs/TEACHING.md): copies the repository's working tree
# (the files git tracks, and new files it does not ignore; no .git) to
# DEST, then replaces the body of every method of Sources/Course marked
#
#     // BEGIN SOLUTION week N: TOPIC — WHAT TO WRITE
#     //   (more of WHAT TO WRITE, each line indented by three spaces)
#     …the model answer…
#     // END SOLUTION
#
# with N ≥ WEEK by a fatalError naming the week, the method, what to write
# and the lecture; the weeks before WEEK keep their answers. The markers
# stay, so that the student sees where to write. Needs bash, git, python3.
# Usage: Scripts/make-handout.sh WEEK DEST   (DEST must not exist, or be
# an empty folder)
set -euo pipefail
if [ $# -ne 2 ] || ! [[ $1 =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: Scripts/make-handout.sh WEEK DEST (WEEK a number, 1 or more)" >&2
  exit 64
fi
week=$1
dest=$2
root=$(cd "$(dirname "$0")/.." && pwd)
if [ -e "$dest" ] && [ -n "$(ls -A "$dest")" ]; then
  echo "make-handout: $dest is not empty; give a new folder" >&2
  exit 1
fi
# Every marker well formed and the week marked, before anything is copied.
python3 "$root/Scripts/handout.py" check "$root" "$week"
mkdir -p "$dest"
dest=$(cd "$dest" && pwd)
if [ "$dest" = "$root" ]; then
  echo "make-handout: DEST is the repository itself" >&2
  exit 1
fi

git -C "$root" ls-files -z --cached --others --exclude-standard |
  python3 "$root/Scripts/handout.py" copy "$root" "$dest"
python3 "$root/Scripts/handout.py" stub "$dest" "$week"
