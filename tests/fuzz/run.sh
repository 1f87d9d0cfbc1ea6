#!/usr/bin/env bash
# Builds the libFuzzer targets with clang and runs each for FUZZ_SECONDS
# (default 60) on a copy of the stored corpus, two at a time: sweep files,
# formulas, derived-counter expressions, CSV tables, results.json, the
# header of a user technique's GLSL file, images (the reader of `diff` and
# of maps).  A crash, leak,
# sanitizer report or broken invariant fails the test; the input that
# triggered it is kept in the work dir and printed.
set -euo pipefail
SRC=${DMBENCH_SOURCE_DIR:?}
SECS=${FUZZ_SECONDS:-60}
WORK=${FUZZ_WORK:-$(mktemp -d)}
cmake -S "$SRC/tests/fuzz" -B "$WORK/build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ > "$WORK/cmake.log" 2>&1 || { cat "$WORK/cmake.log"; exit 1; }
cmake --build "$WORK/build" -j 2 > "$WORK/build.log" 2>&1 || { tail -30 "$WORK/build.log"; exit 1; }
# Two targets at a time (the machine has two cores), FUZZ_SECONDS each.
TARGETS=(sweep formula expr csv results glsl image)
fail=0; pass=0
run_one() {
  local t=$1
  mkdir -p "$WORK/corpus-$t"
  cp "$SRC/tests/fuzz/corpus/$t/"* "$WORK/corpus-$t/"
  local env=()   # NAME.supp: leaks of a library, not of dmbench (full stacks, so they match)
  [ -f "$SRC/tests/fuzz/$t.supp" ] &&
    env=(ASAN_OPTIONS=fast_unwind_on_malloc=0 LSAN_OPTIONS=suppressions="$SRC/tests/fuzz/$t.supp")
  ( cd "$WORK" && env "${env[@]}" ./build/fuzz_$t "corpus-$t" -max_total_time="$SECS" -rss_limit_mb=2048 \
      -artifact_prefix="$WORK/crash-$t-" > "$WORK/$t.log" 2>&1 )
}
report() {
  local t=$1 rc=$2
  if [ "$rc" -eq 0 ]; then
    pass=$((pass+1)); echo "fuzz_$t: $(grep -E '^Done [0-9]+ runs' "$WORK/$t.log" || echo done)"
  else
    fail=$((fail+1)); echo "fuzz_$t FAILED:"; tail -40 "$WORK/$t.log"; ls "$WORK"/crash-$t-* 2>/dev/null || true
  fi
}
for ((i = 0; i < ${#TARGETS[@]}; i += 2)); do
  pids=(); names=()
  for t in "${TARGETS[@]:i:2}"; do run_one "$t" & pids+=($!); names+=("$t"); done
  for k in "${!pids[@]}"; do
    if wait "${pids[$k]}"; then report "${names[$k]}" 0; else report "${names[$k]}" 1; fi
  done
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
