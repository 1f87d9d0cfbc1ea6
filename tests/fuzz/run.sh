#!/usr/bin/env bash
# The libFuzzer targets of the parsers (tests/fuzz/CMakeLists.txt, clang):
# sweep files, formulas, derived-counter expressions, CSV tables,
# results.json, the header of a user technique's GLSL file, images (the
# reader of `diff` and of maps).
#
#   run.sh build     configure and build every target in $FUZZ_WORK/build
#                    (kept between runs: a second run rebuilds what changed)
#   run.sh TARGET    run each input of TARGET's stored corpus once
#                    (tests/fuzz/corpus/TARGET),
#                    then fuzz new inputs for FUZZ_SECONDS (default 5, a
#                    whole number of seconds from 1) on a fresh copy of it
#
# A crash, leak, sanitizer report or broken invariant fails the test; the
# input that triggered it is kept in $FUZZ_WORK and printed.  Each target is
# a ctest test of its own (tests/fuzz.cmake), so ctest runs them side by side.
set -euo pipefail
SRC=${DMBENCH_SOURCE_DIR:?}
WORK=${FUZZ_WORK:?}
# 5 s of new inputs a target in `make test`: the stored corpus, replayed in
# full first, is the regression check; longer runs explore
# (FUZZ_SECONDS=600 ctest -L fuzz, docs/testing.md).
SECS=${FUZZ_SECONDS:-5}
[[ $SECS =~ ^[1-9][0-9]*$ ]] ||
  { echo "FUZZ_SECONDS=$SECS: not a whole number of seconds from 1 (libFuzzer reads 0 as no limit)"; exit 2; }
mkdir -p "$WORK"
if [ "${1:-}" = build ]; then
  launcher=()
  [ -n "${FUZZ_LAUNCHER:-}" ] &&
    launcher=(-DCMAKE_C_COMPILER_LAUNCHER="$FUZZ_LAUNCHER" -DCMAKE_CXX_COMPILER_LAUNCHER="$FUZZ_LAUNCHER")
  # Ninja when it is installed (less CPU than make's dependency scans); a
  # tree kept from a run with the other generator is removed.
  gen="Unix Makefiles"
  command -v ninja > /dev/null && gen=Ninja
  if [ -f "$WORK/build/CMakeCache.txt" ] && ! grep -qx "CMAKE_GENERATOR:INTERNAL=$gen" "$WORK/build/CMakeCache.txt"; then
    echo "removing $WORK/build: configured with another generator than $gen"
    rm -rf "$WORK/build"
  fi
  cmake -S "$SRC/tests/fuzz" -B "$WORK/build" -G "$gen" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    "${launcher[@]}" > "$WORK/cmake.log" 2>&1 || { cat "$WORK/cmake.log"; exit 1; }
  cmake --build "$WORK/build" -j "$(nproc)" > "$WORK/build.log" 2>&1 || { tail -30 "$WORK/build.log"; exit 1; }
  exit 0
fi
t=${1:?usage: run.sh build | run.sh TARGET}
[ -d "$SRC/tests/fuzz/corpus/$t" ] || { echo "no stored corpus for $t"; exit 2; }
[ -x "$WORK/build/fuzz_$t" ] || { echo "fuzz_$t is not built (run.sh build)"; exit 1; }
C="$WORK/corpus-$t"
rm -rf "$C" "$WORK"/crash-"$t"-*
mkdir -p "$C"
cp "$SRC/tests/fuzz/corpus/$t/"* "$C/"
env=()   # NAME.supp: leaks of a library, not of dmbench (full stacks, so they match)
[ -f "$SRC/tests/fuzz/$t.supp" ] &&
  env=(ASAN_OPTIONS=fast_unwind_on_malloc=0 LSAN_OPTIONS=suppressions="$SRC/tests/fuzz/$t.supp")
# The resident-set limit: 2 GB, but 4 GB for the image reader, whose
# OpenImageIO format probing of a malformed 121-byte PNG once took the
# process from 295 MB to 2.4 GB resident with 55 MB of live heap (not
# reproduced when that input ran alone; kept as
# tests/fuzz/known/image-rss-spike.png).  -malloc_limit_mb stays 2048 for
# both, so any single allocation of that size still fails the target.
rss=2048
[ "$t" = image ] && rss=4096
lim=(-rss_limit_mb="$rss" -malloc_limit_mb=2048)
fail() { echo "fuzz_$t FAILED ($1):"; tail -40 "$2"; ls "$WORK"/crash-"$t"-* 2>/dev/null || true; exit 1; }
# 1. The regression check: every stored input run once, as files (libFuzzer
#    runs each and exits).
n=$(ls "$SRC/tests/fuzz/corpus/$t" | wc -l)
t0=$(date +%s)
( cd "$WORK" && env "${env[@]}" "./build/fuzz_$t" "${lim[@]}" -artifact_prefix="$WORK/crash-$t-" \
    "$SRC/tests/fuzz/corpus/$t/"* > "$WORK/$t.replay.log" 2>&1 ) || fail "replaying the stored corpus" "$WORK/$t.replay.log"
ran=$(grep -c '^Running: ' "$WORK/$t.replay.log" || true)
[ "$ran" -eq "$n" ] || fail "$ran of the $n stored inputs ran" "$WORK/$t.replay.log"
r=$(( $(date +%s) - t0 + 1 ))
# 2. New inputs from a copy of the corpus.  libFuzzer's -max_total_time
#    counts from its start, and it runs the copy again first (about as long
#    as step 1 took, r s, rounded up), so it gets SECS + r: about SECS of
#    new inputs.  A run with none fails.
( cd "$WORK" && env "${env[@]}" "./build/fuzz_$t" "$C" -max_total_time=$((SECS + r)) "${lim[@]}" \
    -artifact_prefix="$WORK/crash-$t-" > "$WORK/$t.log" 2>&1 ) || fail "fuzzing" "$WORK/$t.log"
inited=$(sed -n 's/^#\([0-9]*\)[[:space:]]*INITED.*/\1/p' "$WORK/$t.log" | head -1)
done_runs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$WORK/$t.log" | tail -1)
[ -n "$inited" ] && [ -n "$done_runs" ] || fail "no INITED or Done line" "$WORK/$t.log"
[ "$done_runs" -gt "$inited" ] || fail "no new input was run in $((SECS + r)) s" "$WORK/$t.log"
echo "fuzz_$t: $n stored inputs replayed; $((done_runs - inited)) new inputs in $(grep -E '^Done [0-9]+ runs' "$WORK/$t.log")"
