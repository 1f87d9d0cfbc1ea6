#!/usr/bin/env bash
# Power of the paired timing gate (issue 27; figures in docs/ci-gating.md):
# N times `dmbench compare --paired BASE SLOW SWEEP --rounds R`, where SLOW
# is a build whose surface fragment shader does more work per fragment, and
# prints per technique how many of the N comparisons called it REGRESSION
# (the target: a ~10 % slowdown in at least 9 of 10), with the median ratio
# and CI.  Unchanged techniques (texture, whose shader SLOW does not touch)
# must never be REGRESSION.
#
# The slower build: configure a build tree with -DDM_SLOW_STEPS=8 and build
# dmbench_slowshader (tests/instructions.cmake; STEPS=8 makes pom about
# +9 % and normal/parallax +25-30 % instructions per frame), e.g.
#   cmake -S . -B /tmp/slow8 -DDM_SLOW_STEPS=8 && cmake --build /tmp/slow8 --target dmbench_slowshader
# (the binary: /tmp/slow8/tests/dmbench_slowshader)
# Timings are only as good as the machine was quiet: the load average is
# printed with each comparison.  LP_NUM_THREADS=1 as in ci/perf-gate.sh.
# Usage: bench/power.sh BASE_BIN SLOW_BIN [N] [ROUNDS] [SWEEP]
set -uo pipefail
HERE=$(cd "$(dirname "$0")/.." && pwd)
BASE=${1:?usage: bench/power.sh BASE_BIN SLOW_BIN [N] [ROUNDS] [SWEEP]}
SLOW=${2:?usage: bench/power.sh BASE_BIN SLOW_BIN [N] [ROUNDS] [SWEEP]}
N=${3:-10}
ROUNDS=${4:-6}
SWEEP=${5:-$HERE/sweeps/ci.yaml}
export LP_NUM_THREADS=${LP_NUM_THREADS:-1}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
for i in $(seq 1 "$N"); do
  l0=$(cut -d' ' -f1 /proc/loadavg)
  t0=$(date +%s)
  rc=0
  "$BASE" compare --paired "$BASE" "$SLOW" "$SWEEP" --rounds "$ROUNDS" --quiet \
      --json "$OUT/c$i.json" >"$OUT/c$i.txt" 2>&1 || rc=$?
  echo "comparison $i: exit $rc, load $l0 -> $(cut -d' ' -f1 /proc/loadavg), $(( $(date +%s) - t0 )) s"
  [ -s "$OUT/c$i.json" ] || { sed 's/^/  /' "$OUT/c$i.txt" | tail -5; }
done
python3 - "$OUT" "$N" <<'PY'
import glob, json, statistics, sys
out, n = sys.argv[1], int(sys.argv[2])
by = {}
for path in sorted(glob.glob(f"{out}/c*.json")):
    for c in json.load(open(path)).get("configs", []):
        t = c.get("configuration") or c.get("key", "?")   # the short label, e.g. "plane 160×90 · pom"
        by.setdefault(t, []).append(c)
print(f"{'configuration':24} {'REGRESSION':>11} {'INCONCLUSIVE':>13} {'PASS':>5}  median ratio  median CI")
for t, cs in sorted(by.items()):
    v = [c["verdict"] for c in cs]
    ratios = [c["ratio"] for c in cs if isinstance(c.get("ratio"), (int, float))]
    cis = [c["ci95"] for c in cs if c.get("ci95") and None not in c["ci95"]]
    ci = (f"[{statistics.median(a for a, _ in cis):.3f}, {statistics.median(b for _, b in cis):.3f}]"
          if cis else "-")
    r = f"x{statistics.median(ratios):.3f}" if ratios else "-"
    print(f"{t:24} {v.count('REGRESSION'):>4} of {len(v):<4} {v.count('INCONCLUSIVE'):>13} "
          f"{v.count('PASS'):>5}  {r:>12}  {ci}")
PY
