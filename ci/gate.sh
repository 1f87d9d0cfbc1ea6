#!/usr/bin/env bash
# The project's CI gate: runs ci/gate.yaml (normal on three meshes) and
# ci/gate-techniques.yaml (every technique with the axes that change its
# shaders or work) with the given dmbench binary and compares their
# deterministic counters with ci/baseline.json and ci/baseline-techniques.json
# (exit 0 pass, 1 a counter changed, 2 bad input), and their Instructions
# (counted under Valgrind) beyond the 0.5 % threshold, so a shader that got
# more expensive fails CI.  Timing is not gated here, so no noise can fail
# CI.  Instruction counts depend on the CPU: on a CPU other than the
# baseline's they are not compared (a warning says so; regenerate the
# baseline on that runner).
# Usage: ci/gate.sh [DMBENCH_BINARY] [OUT_DIR]
# To accept an intended change of the counts: ci/gate.sh --update
# The baselines are per driver (docs/drivers.md): ci/baseline.json and
# ci/baseline-techniques.json for the default driver, ci/baseline-NAME.json
# and ci/baseline-techniques-NAME.json under DMBENCH_DRIVER=NAME.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
if [ "${1:-}" = "--update" ]; then UPDATE=1; shift; else UPDATE=0; fi
BIN=${1:-$HERE/../build/dmbench}
OUT=${2:-$(mktemp -d)}
DRIVER=${DMBENCH_DRIVER:-default}
export LP_NUM_THREADS=${LP_NUM_THREADS:-1}
rc=0
# gate_one SWEEP BASELINE_STEM: runs SWEEP into $OUT/STEM, then updates or
# compares with ci/STEM[-DRIVER].json; raises rc.
gate_one() {
  local sweep=$1 stem=$2 base out=$OUT/$2 r=0
  if [ "$DRIVER" = default ]; then base=$HERE/$stem.json; else base=$HERE/$stem-$DRIVER.json; fi
  "$BIN" run "$HERE/$sweep" --out "$out" --seed 1 --quiet
  if [ "$UPDATE" = 1 ]; then
    cp "$out/latest/results.json" "$base"
    echo "ci/$(basename "$base") updated from $out/latest; commit it with the reason for the change"
    return 0
  fi
  if [ ! -f "$base" ]; then
    echo "ci/gate.sh: no baseline for driver '$DRIVER' ($base): create it with DMBENCH_DRIVER=$DRIVER ci/gate.sh --update" >&2
    exit 2
  fi
  "$BIN" compare --counters-only "$base" "$out/latest" \
    --markdown "$out/gate.md" --junit "$out/gate.xml" || r=$?
  # A gate that compares nothing cannot fail: every baseline configuration
  # must be in the new run (keys change when a technique's version or the
  # scene axes change; then the counts must be checked and the baseline
  # regenerated with --update).
  if [ "$r" = 0 ] && grep -q '^- removed:' "$out/gate.md"; then
    echo "ci/gate.sh: $(grep -c '^- removed:' "$out/gate.md") configuration(s) of ci/$(basename "$base")" \
         "missing from this run (configuration keys changed?); check the counts and run ci/gate.sh --update" >&2
    r=1
  fi
  grep -q "Instructions not compared" "$out/gate.md" 2>/dev/null &&
    echo "ci/gate.sh: warning: Instructions of $sweep not gated: the baseline was counted on another CPU" >&2
  [ "$r" -gt "$rc" ] && rc=$r
  return 0
}
gate_one gate.yaml baseline
gate_one gate-techniques.yaml baseline-techniques
exit "$rc"
