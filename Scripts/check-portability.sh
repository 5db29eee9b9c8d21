#!/usr/bin/env bash
# The portability check .ci/run runs: what would keep the package from
# building on macOS 14+ (Xcode 16, Swift 6.0) while Linux builds it fine.
# Prints one line per violation, FILE:LINE: problem, and exits 1 if any.
#
#  1. The C library's module is named only in Sources/PlatformSupport/
#     (and in the stand-ins for swift-numerics and swift-argument-parser,
#     which keep their own imports as the real packages do).
#  2. Every `import Glibc` has a Darwin branch in the same #if chain, and
#     no call is qualified by the module (`Glibc.write`, `Darwin.pipe`).
#  3. Nothing that needs macOS 15 or later: the Synchronization module
#     (Atomic, Mutex) or Int128/UInt128 outside an `#available` guard.
#  4. Float80 only where x86 is tested for (it does not exist on Apple
#     silicon), or in the reference type ReferenceScalar.
#  5. Package.swift declares no platforms newer than macOS 14.
set -uo pipefail
cd "$(dirname "$0")/.."

failures=0
fail() {
  echo "$1"
  failures=$((failures + 1))
}

swift_files() {
  find Sources Tests Fuzz -name '*.swift' | sort
}

# 1 and 2: imports of the C library.
while IFS= read -r file; do
  case $file in
    Sources/PlatformSupport/* | Sources/RealModule/* | Sources/ArgumentParser/*) allowed=1 ;;
    *) allowed=0 ;;
  esac
  while IFS=: read -r line text; do
    if [ "$allowed" = 0 ]; then
      fail "$file:$line: imports the C library outside Sources/PlatformSupport ($text)"
    fi
  done < <(grep -nE '^\s*(@_exported\s+)?import\s+(Glibc|Darwin|Musl)\b' "$file")
  # Each Glibc import's #if chain must also name Darwin.
  awk -v file="$file" '
    /^[ \t]*#if/ { chain = ""; start = NR }
    { chain = chain "\n" $0 }
    /^[ \t]*#endif/ {
      if (chain ~ /import[ \t]+Glibc/ && chain !~ /canImport\(Darwin\)/)
        printf "%s:%d: imports Glibc without a Darwin branch\n", file, start
      chain = ""
    }
  ' "$file" | while IFS= read -r message; do echo "$message"; done > /tmp/portability.$$
  if [ -s /tmp/portability.$$ ]; then
    while IFS= read -r message; do fail "$message"; done < /tmp/portability.$$
  fi
  rm -f /tmp/portability.$$
  # The stand-ins qualify `exit` as the real argument parser does, in
  # #if branches for each C library.
  case "$file" in Sources/RealModule/* | Sources/ArgumentParser/*) continue ;; esac
  while IFS=: read -r line _; do
    fail "$file:$line: a call qualified by the C library's module"
  done < <(grep -nE '\b(Glibc|Darwin)\.[a-z_]' "$file" | grep -vE '^\s*[0-9]+:\s*//')
done < <(swift_files)

# 3: APIs of macOS 15 and later.
while IFS=: read -r file line _; do
  fail "$file:$line: the Synchronization module needs macOS 15"
done < <(swift_files | xargs grep -nE '^\s*import\s+Synchronization\b')
# A file that uses Int128 must guard it with an availability check for
# macOS 15 (checked per file: the check catches a use nobody guarded).
while IFS= read -r file; do
  grep -qE '[#@]available\(macOS 15' "$file" && continue
  grep -nE '(^|[^A-Za-z0-9_])U?Int128([^A-Za-z0-9_]|$)' "$file" \
    | grep -vE '^[0-9]+:\s*//' | while IFS=: read -r line _; do
      echo "$file:$line: Int128 needs macOS 15: guard it with #available"
    done
done < <(swift_files) > /tmp/portability.$$
while IFS= read -r message; do fail "$message"; done < /tmp/portability.$$
rm -f /tmp/portability.$$

# 4: Float80 outside an x86 #if (the reference type's own file aside).
while IFS= read -r file; do
  awk -v file="$file" '
    /^[ \t]*#if.*arch\((x86_64|i386)\)/ { depth++ ; x86 = depth }
    /^[ \t]*#if/ && !/arch\((x86_64|i386)\)/ { depth++ }
    /^[ \t]*#else/ || /^[ \t]*#elseif/ { if (x86 == depth) x86 = -x86 }
    /^[ \t]*#endif/ { if (x86 == depth || -x86 == depth) x86 = 0; depth-- }
    /Float80/ && !/^[ \t]*\/\// && !/\/\/\/|\/\/ / && x86 <= 0 {
      printf "%s:%d: Float80 outside an x86 #if (Apple silicon has none)\n", file, NR
    }
  ' "$file"
done < <(swift_files | grep -v '^Sources/RealModule/') > /tmp/portability.$$
while IFS= read -r message; do fail "$message"; done < /tmp/portability.$$
rm -f /tmp/portability.$$

# 5: platforms.
if grep -nE '\.macOS\(\.v(1[5-9]|[2-9][0-9])' Package.swift; then
  fail "Package.swift: requires a macOS newer than 14"
fi

if [ "$failures" -gt 0 ]; then
  echo "portability: $failures problem(s)"
  exit 1
fi
echo "portability: ok (C library only in System/, Darwin branches, nothing of macOS 15, Float80 guarded)"
