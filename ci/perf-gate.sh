#!/usr/bin/env bash
# The CI recipe of docs/ci-gating.md, as the job runs it: two gates of a
# pull request's build (NEW) against its target branch's build (BASE).
#   1. the instruction gate: each build runs sweeps/ci-instructions.yaml
#      once; `compare --counters-only` fails on any change of a count and on
#      more than 0.5 % more instructions per frame (exact on llvmpipe: no
#      statistics, never flaky);
#   2. the paired timing gate: `compare --paired` runs both builds on
#      sweeps/ci.yaml in alternating rounds (ABBA), so a machine that
#      changes during the job changes both sides.
# Writes OUT/instructions.{md,xml} and OUT/timing.{md,xml,json}; OUT/perf.md
# holds both Markdown reports (post it as the PR comment).
# Exit: the worst of the two gates — 1 regression, 2 bad input (fix the
# job), 4 environment failure (retry), 3 timing inconclusive (warn), 0 pass.
# Usage: ci/perf-gate.sh BASE_BINARY NEW_BINARY [OUT]
#   env: ROUNDS (default 6), SWEEP (sweeps/ci.yaml),
#        INSTR_SWEEP (sweeps/ci-instructions.yaml)
set -uo pipefail
HERE=$(cd "$(dirname "$0")/.." && pwd)
BASE=${1:?usage: ci/perf-gate.sh BASE_BINARY NEW_BINARY [OUT]}
NEW=${2:?usage: ci/perf-gate.sh BASE_BINARY NEW_BINARY [OUT]}
OUT=${3:-perf}
ROUNDS=${ROUNDS:-6}
SWEEP=${SWEEP:-$HERE/sweeps/ci.yaml}
INSTR_SWEEP=${INSTR_SWEEP:-$HERE/sweeps/ci-instructions.yaml}
export LP_NUM_THREADS=${LP_NUM_THREADS:-1}
mkdir -p "$OUT"

# 1. instruction gate
irc=0
"$BASE" run "$INSTR_SWEEP" --out "$OUT/base-instructions" --seed 1 --quiet || irc=$?
[ "$irc" = 0 ] && { "$NEW" run "$INSTR_SWEEP" --out "$OUT/new-instructions" --seed 1 --quiet || irc=$?; }
[ "$irc" = 0 ] && { "$NEW" compare --counters-only "$OUT/base-instructions" "$OUT/new-instructions" \
    --markdown "$OUT/instructions.md" --junit "$OUT/instructions.xml" --quiet || irc=$?; }

# 2. paired timing gate
trc=0
"$NEW" compare --paired "$BASE" "$NEW" "$SWEEP" --rounds "$ROUNDS" --quiet \
    --markdown "$OUT/timing.md" --junit "$OUT/timing.xml" --json "$OUT/timing.json" || trc=$?

{ cat "$OUT/instructions.md" 2>/dev/null; echo; cat "$OUT/timing.md" 2>/dev/null; } > "$OUT/perf.md"
# The worst code wins: a failure of the job or the machine before a verdict.
rc=0
for c in 2 4 1 3; do
  if [ "$irc" = "$c" ] || [ "$trc" = "$c" ]; then rc=$c; break; fi
done
case $rc in
  0) echo "perf gate: pass (instructions exit $irc, timing exit $trc)" ;;
  1) echo "perf gate: REGRESSION — see $OUT/perf.md; if intended, say why in the PR" ;;
  2) echo "perf gate: bad input or usage — the job is wrong, not the code (instructions exit $irc, timing exit $trc)" ;;
  3) echo "perf gate: timing inconclusive — no verdict either way; re-run with ROUNDS=$((ROUNDS * 2))" ;;
  4) echo "perf gate: environment failure (disk, store, GL driver) — retry the job" ;;
esac
exit "$rc"
