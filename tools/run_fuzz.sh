#!/usr/bin/env bash
# Builds the mesh-reader fuzzers (libFuzzer, clang, ASan+UBSan; the "fuzz" CMake preset) and runs
# each one for SECONDS (default 30), seeded from tests/fuzz/corpus/<reader>/. Exits non-zero when
# any fuzzer finds a crash, a leak, a timeout or a broken invariant; the input that did it is saved
# as BUILD/fuzz-out/<reader>/crash-* (reproduce: BUILD/tests/fuzz/fuzz_<reader> FILE).
#
# Usage: tools/run_fuzz.sh [SECONDS] [BUILD_DIR]     (BUILD_DIR defaults to build/fuzz)
set -euo pipefail

seconds=${1:-30}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${2:-$root/build/fuzz}
jobs=${JOBS:-2}
cd "$root"

mkdir -p "$build"
cmake --preset fuzz -B "$build" > "$build/configure.log" 2>&1 || {
  cat "$build/configure.log"; exit 2; }
cmake --build "$build" --target fuzz_gmsh fuzz_tetgen fuzz_vtk -j "$jobs"

status=0
for reader in gmsh tetgen vtk; do
  out=$build/fuzz-out/$reader
  mkdir -p "$out/corpus"
  rm -f "$out"/crash-* "$out"/leak-* "$out"/timeout-* "$out"/oom-*
  echo "== fuzz_$reader for ${seconds}s"
  # New inputs go to $out/corpus; the committed seeds are only read.
  if ! "$build/tests/fuzz/fuzz_$reader" "$out/corpus" "tests/fuzz/corpus/$reader" \
        -dict="tests/fuzz/$reader.dict" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
        -rss_limit_mb=2048 -artifact_prefix="$out/" -print_final_stats=1 2>&1 | tail -n 25; then
    status=1
  fi
  if compgen -G "$out/crash-*" > /dev/null || compgen -G "$out/leak-*" > /dev/null ||
     compgen -G "$out/timeout-*" > /dev/null || compgen -G "$out/oom-*" > /dev/null; then
    echo "fuzz_$reader: failing inputs in $out" >&2
    status=1
  fi
done
exit $status
