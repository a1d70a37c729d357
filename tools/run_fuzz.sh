#!/usr/bin/env bash
# Builds the fuzzers (libFuzzer, clang, ASan+UBSan; the "fuzz" CMake preset) of the mesh readers,
# the scene loader and the recording reader, and runs each one for SECONDS (default 30), seeded
# from tests/fuzz/corpus/<reader>/. Exits non-zero when any fuzzer finds a crash, a leak, a
# timeout or a broken invariant; the input that did it is saved as BUILD/fuzz-out/<reader>/crash-*
# (reproduce: BUILD/tests/fuzz/fuzz_<reader> FILE). `tools/setup fuzz` runs it (60 s each) in CI.
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
readers=(gmsh tetgen vtk scene recording)
cmake --build "$build" --target "${readers[@]/#/fuzz_}" -j "$jobs"

status=0
for reader in "${readers[@]}"; do
  # Inputs may grow to twice the largest seed (4 KiB at least): the recording seeds, a header
  # holding the whole scene text and then the steps, are the largest.
  max_len=4096
  for seed in "tests/fuzz/corpus/$reader"/*; do
    size=$(stat -c %s "$seed")
    if ((2 * size > max_len)); then max_len=$((2 * size)); fi
  done
  out=$build/fuzz-out/$reader
  mkdir -p "$out/corpus"
  rm -f "$out"/crash-* "$out"/leak-* "$out"/timeout-* "$out"/oom-*
  echo "== fuzz_$reader for ${seconds}s"
  # New inputs go to $out/corpus; the committed seeds are only read.
  if ! "$build/tests/fuzz/fuzz_$reader" "$out/corpus" "tests/fuzz/corpus/$reader" \
        -dict="tests/fuzz/$reader.dict" -max_total_time="$seconds" -max_len="$max_len" -timeout=10 \
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
