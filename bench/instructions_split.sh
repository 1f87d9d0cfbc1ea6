#!/usr/bin/env bash
# Where the Instructions pass spends its time (issue: a pass several times
# faster).  Runs SWEEP (default ci/gate.yaml, whose counters include
# Instructions) twice into fresh output roots: as it is, and without
# Instructions; the difference in wall time is the pass.  The counting
# child logs its own split (run/measure.c, "instructions split:" lines in
# <run>/callgrind/child.log): GL context, then per configuration prepare
# (maps, meshes, program link), warm-up (incl. llvmpipe's JIT at the first
# draw and the discarded first sample) and the kept counted samples; the
# rest of the pass is Valgrind's start-up and exit and the parent's reading
# of the dumps.  Times are wall times under Valgrind, only as good as the
# machine was quiet (the load average is printed).
# Usage: bench/instructions_split.sh BIN [SWEEP]
set -euo pipefail
BIN=${1:?usage: bench/instructions_split.sh path/to/dmbench [SWEEP]}
HERE=$(cd "$(dirname "$0")" && pwd)
SWEEP=${2:-$HERE/../ci/gate.yaml}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
python3 - "$SWEEP" "$OUT/plain.yaml" <<'PY'
import re, sys
text = "".join(l for l in open(sys.argv[1]) if not l.lstrip().startswith("#"))
text = re.sub(r",\s*InstructionsPerPixel\b", "", text)
text = re.sub(r",\s*Instructions\b", "", text)
text = re.sub(r"\[\s*Instructions\s*\]", "[WallTime]", text)
assert "Instructions" not in text, "the sweep lists Instructions where this script cannot remove it"
open(sys.argv[2], "w").write(text)
PY
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
t0=$(date +%s.%N)
"$BIN" run "$SWEEP" --out "$OUT/with" --seed 1 --quiet
t1=$(date +%s.%N)
"$BIN" run "$OUT/plain.yaml" --out "$OUT/without" --seed 1 --quiet
t2=$(date +%s.%N)
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$OUT/with" "$t0" "$t1" "$t2" <<'PY'
import glob, re, sys
root, t0, t1, t2 = sys.argv[1], *map(float, sys.argv[2:])
pass_s = (t1 - t0) - (t2 - t1)
ctx = prep = warm = count = 0.0
n = 0
for log in glob.glob(f"{root}/2*/callgrind/child.log"):   # the run directory, not the latest link
    for line in open(log, errors="replace"):
        m = re.search(r"instructions split: context ([\d.]+) ms", line)
        if m:
            ctx += float(m.group(1)) / 1e3
        m = re.search(r"prepare ([\d.]+) ms, warm-up ([\d.]+) ms, counted ([\d.]+) ms", line)
        if m:
            n += 1
            prep += float(m.group(1)) / 1e3; warm += float(m.group(2)) / 1e3; count += float(m.group(3)) / 1e3
rest = pass_s - ctx - prep - warm - count
print(f"run with Instructions {t1 - t0:.1f} s, without {t2 - t1:.1f} s: the pass {pass_s:.1f} s for {n} configurations")
for what, s in (("Valgrind start-up/exit, reading dumps (the rest)", rest), ("GL context", ctx),
                ("prepare: maps, meshes, program link", prep), ("warm-up: first draw's JIT, discarded sample", warm),
                ("counted frames (kept samples)", count)):
    print(f"  {what:48} {s:7.1f} s  {100 * s / pass_s if pass_s > 0 else 0:5.1f} %")
if n:
    print(f"  per configuration: {pass_s / n:.1f} s")
PY
