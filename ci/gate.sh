#!/usr/bin/env bash
# The project's CI gate: runs ci/gate.yaml with the given dmbench binary and
# compares its deterministic counters with ci/baseline.json (exit 0 pass,
# 1 a counter changed, 2 bad input), and its Instructions (counted under
# Valgrind) beyond the 0.5 % threshold, so a shader that got more expensive
# fails CI.  Timing is not gated here, so no noise can fail CI.  Instruction
# counts depend on the CPU: on a CPU other than the baseline's they are not
# compared (a warning says so; regenerate the baseline on that runner).
# Usage: ci/gate.sh [DMBENCH_BINARY] [OUT_DIR]
# To accept an intended change of the counts: ci/gate.sh --update
# The baseline is per driver (docs/drivers.md): ci/baseline.json for the
# default driver, ci/baseline-NAME.json under DMBENCH_DRIVER=NAME.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
if [ "${1:-}" = "--update" ]; then UPDATE=1; shift; else UPDATE=0; fi
BIN=${1:-$HERE/../build/dmbench}
OUT=${2:-$(mktemp -d)}
DRIVER=${DMBENCH_DRIVER:-default}
if [ "$DRIVER" = default ]; then BASE=$HERE/baseline.json; else BASE=$HERE/baseline-$DRIVER.json; fi
export LP_NUM_THREADS=${LP_NUM_THREADS:-1}
"$BIN" run "$HERE/gate.yaml" --out "$OUT" --seed 1 --quiet
if [ "$UPDATE" = 1 ]; then
  cp "$OUT/latest/results.json" "$BASE"
  echo "ci/$(basename "$BASE") updated from $OUT/latest; commit it with the reason for the change"
  exit 0
fi
if [ ! -f "$BASE" ]; then
  echo "ci/gate.sh: no baseline for driver '$DRIVER' ($BASE): create it with DMBENCH_DRIVER=$DRIVER ci/gate.sh --update" >&2
  exit 2
fi
rc=0
"$BIN" compare --counters-only "$BASE" "$OUT/latest" \
  --markdown "$OUT/gate.md" --junit "$OUT/gate.xml" || rc=$?
# A gate that compares nothing cannot fail: every baseline configuration
# must be in the new run (keys change when a technique's version or the
# scene axes change; then the counts must be checked and the baseline
# regenerated with --update).
if [ "$rc" = 0 ] && grep -q '^- removed:' "$OUT/gate.md"; then
  echo "ci/gate.sh: $(grep -c '^- removed:' "$OUT/gate.md") baseline configuration(s) missing from this run" \
       "(configuration keys changed?); check the counts and run ci/gate.sh --update" >&2
  rc=1
fi
grep -q "Instructions not compared" "$OUT/gate.md" 2>/dev/null &&
  echo "ci/gate.sh: warning: Instructions not gated: the baseline was counted on another CPU" >&2
exit "$rc"
