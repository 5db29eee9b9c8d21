#!/usr/bin/env bash
# Builds the libFuzzer harnesses with swiftc and runs one of them.
#
#   Fuzz/run.sh [scene|plist|obj|bmp|cli] [LIBFUZZER OPTION...]
#   Fuzz/run.sh build            # build every fuzzer, run nothing
#
#   Fuzz/run.sh scene -runs=10000000
#   Fuzz/run.sh cli -max_total_time=600
#   Fuzz/run.sh scene .build/fuzz/crash-scene/crash-1234   # replay one input
#
# Harnesses: Fuzz/FuzzSceneParser.swift (scene files, then a 4x3 render of
# whatever parses) and Fuzz/FuzzCommandLine.swift (arguments split at NUL
# bytes, parsed and validated, never run) and Fuzz/FuzzOBJReader.swift (OBJ
# files: a mesh with indices in range, or one well-formed error),
# Fuzz/FuzzPlistScene.swift (property-list scenes, then a 4x3 render) and
# Fuzz/FuzzBMPReader.swift (texture files). See each file's header for what
# it checks.
#
# Why not SwiftPM: it cannot build a libFuzzer target (its products would
# get libFuzzer's main), so each module is compiled here with swiftc, the
# same sources SwiftPM compiles, instrumented with -sanitize=fuzzer,address:
#   RealModule, ArgumentParser     the stand-ins, as they are, or the real
#                                  packages' modules (below)
#   Geometry, SceneDescription, Course, PlatformSupport, ExactArithmetic,
#   SceneIO, FastKernels, FastEngine, Pipeline, Measurement
#                                  the library's targets in the order they
#                                  import each other, -enable-testing: the
#                                  fuzzer reaches the internal
#                                  SceneParser.parse(bytes:file:)
#   raytrace                       the executable's sources, @main included,
#                                  its entry point renamed raytrace_main (as
#                                  SwiftPM does when tests link an executable)
# Everything goes to .build/fuzz/ (git-ignored): objects, the fuzzers, the
# working corpora corpus-scene/ and corpus-cli/ (libFuzzer adds what it finds
# there; the committed seeds in Fuzz/corpus/ are read, never written), and
# crash-scene/ and crash-cli/ for inputs that fail.
#
# Environment:
#   FUZZ_OPT="-Onone"   optimisation (default -O: measured 7,000 executions
#                       per second on the scene fuzzer against 1,400 with
#                       -Onone, which finds slightly more edges per input)
#   FUZZ_SANITIZERS=fuzzer
#                       coverage only, no AddressSanitizer (default
#                       fuzzer,address); objects go to .build/fuzz/obj-O-noasan/.
#                       For harnesses whose code holds no unsafe pointer
#                       (the command line): Swift's own checks trap on
#                       every out-of-bounds access and overflow, and the
#                       harness runs about twice as fast (docs/ROBUSTNESS.md)
#   FUZZ_STRICT=1       scene fuzzer: also require finite unit normals and
#                       finite colours of every hit (see the harness)
#   SWIFTC              the compiler (default: swiftc on PATH)
#   RAYTRACE_PACKAGES, RAYTRACE_ARGUMENT_PARSER_PATH, RAYTRACE_NUMERICS_PATH
#                       as for Package.swift (docs/PORTABILITY.md, "Packages"): the
#                       real swift-argument-parser and swift-numerics
#                       instead of the stand-ins, their modules compiled
#                       from the local checkouts or, for 'apple', from
#                       .build/checkouts/ (swift package resolve); objects
#                       then go to .build/fuzz/obj-real*/
#
# Defaults passed to libFuzzer, overridable by repeating the option:
# -timeout=10 (an input taking seconds is a finding), -rss_limit_mb=2048,
# -print_final_stats=1, the dictionary of the format's keywords. One worker:
# the machine's other core is left free.
set -euo pipefail

cd "$(dirname "$0")/.."
swiftc=${SWIFTC:-swiftc}
opt=${FUZZ_OPT:--O}
mode=${1:-scene}
[ $# -gt 0 ] && shift

build=.build/fuzz
sanitizers=${FUZZ_SANITIZERS:-fuzzer,address}
case $sanitizers in
  fuzzer | fuzzer,address) ;;
  *)
    echo "FUZZ_SANITIZERS='$sanitizers': expected 'fuzzer,address' or 'fuzzer'" >&2
    exit 64
    ;;
esac
variant=${opt// /}
[ "$sanitizers" = fuzzer ] && variant+=-noasan
objects=$build/obj$variant
flags=(-parse-as-library -wmo -gline-tables-only $opt -sanitize=$sanitizers
  -package-name raytrace)

# The two packages: the stand-ins' folders, or the real packages' checkouts
# chosen as Package.swift chooses them.
parser_path=${RAYTRACE_ARGUMENT_PARSER_PATH:-}
numerics_path=${RAYTRACE_NUMERICS_PATH:-}
packages=${RAYTRACE_PACKAGES:-}
if [ -n "$packages$parser_path$numerics_path" ]; then
  case $packages in
    '' | apple) ;;
    *:*)
      parser_path=${parser_path:-${packages%%:*}}
      numerics_path=${numerics_path:-${packages#*:}}
      ;;
    *)
      echo "RAYTRACE_PACKAGES='$packages': expected 'apple' or" \
        "PARSER_CHECKOUT:NUMERICS_CHECKOUT" >&2
      exit 64
      ;;
  esac
  if [ -z "$parser_path" ] || [ -z "$numerics_path" ]; then
    swift package resolve >&2
    parser_path=${parser_path:-.build/checkouts/swift-argument-parser}
    numerics_path=${numerics_path:-.build/checkouts/swift-numerics}
  fi
  objects=$build/obj-real$variant
fi
mkdir -p "$objects"

# Compiles module $1 from the .swift files under $2 unless its object is
# newer than all of them; extra swiftc flags follow.
compile() {
  local module=$1 folder=$2
  shift 2
  local object=$objects/$module.o
  if [ -f "$object" ] && [ -z "$(find "$folder" -name '*.swift' -newer "$object")" ]; then
    return
  fi
  echo "compiling $module" >&2
  local sources
  mapfile -t sources < <(find "$folder" -name '*.swift' | sort)
  "$swiftc" "${flags[@]}" -module-name "$module" -I "$objects" "$@" \
    -emit-module -emit-module-path "$objects/$module.swiftmodule" \
    -c "${sources[@]}" -o "$object"
}

# RealModule, and what it needs: the real one imports the C module
# _NumericsShims (a header of inline functions).
numerics_flags=()
compile_real_module() {
  if [ -z "$numerics_path" ]; then
    compile RealModule Sources/RealModule
    return
  fi
  local shims=$numerics_path/Sources/_NumericsShims/include/module.modulemap
  numerics_flags=(-Xcc "-fmodule-map-file=$shims")
  compile RealModule "$numerics_path/Sources/RealModule" "${numerics_flags[@]}"
}

# ArgumentParser, and the objects to link: the real one imports
# ArgumentParserToolInfo.
parser_objects=()
compile_argument_parser() {
  if [ -z "$parser_path" ]; then
    compile ArgumentParser Sources/ArgumentParser
    parser_objects=("$objects/ArgumentParser.o")
    return
  fi
  compile ArgumentParserToolInfo "$parser_path/Sources/ArgumentParserToolInfo"
  compile ArgumentParser "$parser_path/Sources/ArgumentParser"
  parser_objects=("$objects/ArgumentParser.o" \
    "$objects/ArgumentParserToolInfo.o")
}

# The library's targets, each compiled after those it imports.
library_objects=()
compile_library() {
  compile_real_module
  local module
  library_objects=()
  for module in Geometry SceneDescription Course PlatformSupport ExactArithmetic \
    SceneIO FastKernels FastEngine Pipeline Measurement; do
    compile "$module" "Sources/$module" -enable-testing "${numerics_flags[@]}" \
      -Xcc -fmodule-map-file=Sources/CZlib/module.modulemap
    library_objects+=("$objects/$module.o")
  done
}

build_scene() {
  compile_library
  echo "linking fuzz-scene" >&2
  "$swiftc" "${flags[@]}" -I "$objects" \
    -Xcc -fmodule-map-file=Sources/CZlib/module.modulemap "${numerics_flags[@]}" \
    Fuzz/FuzzSceneParser.swift "${library_objects[@]}" "$objects/RealModule.o" \
    -lz -use-ld=lld -o "$objects/fuzz-scene"
}

build_obj() {
  compile_library
  echo "linking fuzz-obj" >&2
  "$swiftc" "${flags[@]}" -I "$objects" \
    -Xcc -fmodule-map-file=Sources/CZlib/module.modulemap "${numerics_flags[@]}" \
    Fuzz/FuzzOBJReader.swift "${library_objects[@]}" "$objects/RealModule.o" \
    -lz -use-ld=lld -o "$objects/fuzz-obj"
}

# A harness of the library alone: build_library NAME FILE.
build_library() {
  compile_library
  echo "linking fuzz-$1" >&2
  "$swiftc" "${flags[@]}" -I "$objects" \
    -Xcc -fmodule-map-file=Sources/CZlib/module.modulemap "${numerics_flags[@]}" \
    "$2" "${library_objects[@]}" "$objects/RealModule.o" \
    -lz -use-ld=lld -o "$objects/fuzz-$1"
}

build_cli() {
  compile_library
  compile_argument_parser
  compile raytrace Sources/raytrace -enable-testing "${numerics_flags[@]}" \
    -Xcc -fmodule-map-file=Sources/CZlib/module.modulemap \
    -Xfrontend -entry-point-function-name -Xfrontend raytrace_main
  echo "linking fuzz-cli" >&2
  "$swiftc" "${flags[@]}" -I "$objects" \
    -Xcc -fmodule-map-file=Sources/CZlib/module.modulemap "${numerics_flags[@]}" \
    Fuzz/FuzzCommandLine.swift "$objects/raytrace.o" \
    "${parser_objects[@]}" "${library_objects[@]}" \
    "$objects/RealModule.o" -lz -use-ld=lld -o "$objects/fuzz-cli"
}

case $mode in
  build)
    build_scene
    build_cli
    build_obj
    build_library plist Fuzz/FuzzPlistScene.swift
    build_library bmp Fuzz/FuzzBMPReader.swift
    exit 0
    ;;
  plist)
    build_library plist Fuzz/FuzzPlistScene.swift
    dictionary=Fuzz/plist.dict
    ;;
  bmp)
    build_library bmp Fuzz/FuzzBMPReader.swift
    dictionary=Fuzz/bmp.dict
    ;;
  obj)
    build_obj
    dictionary=Fuzz/obj.dict
    ;;
  scene)
    build_scene
    dictionary=Fuzz/scene.dict
    ;;
  cli)
    build_cli
    dictionary=Fuzz/cli.dict
    ;;
  *)
    echo "usage: Fuzz/run.sh [scene|plist|obj|bmp|cli|build] [libFuzzer option...]" >&2
    exit 64
    ;;
esac

corpus=$build/corpus-$mode
crashes=$build/crash-$mode
mkdir -p "$corpus" "$crashes"

# An argument that names a file replays it (and any others) instead of
# fuzzing the corpora.
inputs=("$corpus" "Fuzz/corpus/$mode")
for argument in "$@"; do
  if [ -f "$argument" ]; then
    inputs=()
    break
  fi
done

# The Swift runtime's backtracer would take the trap of a failed check
# before libFuzzer (which leaves a handler already installed alone), and
# then neither save the input nor exit.
export SWIFT_BACKTRACE=enable=no
# Leaks of Foundation's own, not the package's (Fuzz/lsan.supp says which).
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=Fuzz/lsan.supp}
exec "$objects/fuzz-$mode" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -dict="$dictionary" -artifact_prefix="$crashes/" "$@" "${inputs[@]}"
