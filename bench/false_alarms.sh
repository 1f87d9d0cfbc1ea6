#!/usr/bin/env bash
# False alarms of the timing gate between separate runs (issue 27; figures
# in docs/ci-gating.md): PAIRS pairs of `dmbench run --quick` of the same
# binary, compared with `dmbench compare BASE NEW`.  In every second pair a
# CPU-heavy job (BUSY busy processes, default 1) runs from just
# after BASE until NEW is done — the machine changed between the runs.
# Prints per pair: loads, the machine checks' reason, the verdict counts
# and the exit code; at the end the REGRESSION count (the target is 0).
# Compare binaries: COMPARE_BIN (default BIN) — e.g. an older build, to
# show what its verdicts were on the same runs.
# Usage: bench/false_alarms.sh BIN [PAIRS] [OUT]   (PAIRS default 20)
set -uo pipefail
BIN=${1:?usage: false_alarms.sh path/to/dmbench [PAIRS] [OUT]}
PAIRS=${2:-20}
OUT=${3:-$(mktemp -d)}
CMP=${COMPARE_BIN:-$BIN}
mkdir -p "$OUT"
load() { cut -d' ' -f1 /proc/loadavg; }
regressions=0; alarms=0
for p in $(seq 1 "$PAIRS"); do
  busy=$(( p % 2 == 0 ))
  l0=$(load)
  "$BIN" run --quick --quiet --out "$OUT/p$p-base" >/dev/null 2>&1 || { echo "pair $p: BASE run failed"; continue; }
  pids=()
  if [ $busy = 1 ]; then
    for _ in $(seq 1 "${BUSY:-1}"); do timeout 300 sh -c 'while :; do :; done' & pids+=($!); done
    sleep 5
  fi
  l1=$(load)
  "$BIN" run --quick --quiet --out "$OUT/p$p-new" >/dev/null 2>&1 || echo "pair $p: NEW run failed"
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  wait 2>/dev/null
  rc=0
  "$CMP" compare "$OUT/p$p-base" "$OUT/p$p-new" --json "$OUT/p$p.json" >"$OUT/p$p.txt" 2>&1 || rc=$?
  n=$(grep -c '^REGRESSION' "$OUT/p$p.txt")
  regressions=$((regressions + n)); [ "$n" -gt 0 ] && alarms=$((alarms + 1))
  reason=$(grep -m1 '^machine: [^B]' "$OUT/p$p.txt" | cut -c10-)
  echo "pair $p (CPU job between: $([ $busy = 1 ] && echo yes || echo no)): load $l0 -> $l1, exit $rc," \
       "$(tail -1 "$OUT/p$p.txt" | cut -d';' -f1); machine: ${reason:-(not reported)}"
done
echo "false alarms: $alarms of $PAIRS pairs had a REGRESSION ($regressions configurations); output in $OUT"
