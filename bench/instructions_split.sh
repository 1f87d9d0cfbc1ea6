#!/usr/bin/env bash
# Where the Instructions pass spends its time (issue: a pass several times
# faster).  Runs SWEEP (default ci/gate.yaml, whose counters include
# Instructions) twice into fresh output roots: as it is, and without
# Instructions, and prints both wall times and their ratio.  The pass's own
# wall time is the run's "instructions counted in" line.  Each counting
# child (`run --count-jobs`; one per CPU by default) logs its split
# (run/count_child.c, "instructions split:" lines in <run>/callgrind/child*.log):
# GL context, then per configuration prepare (maps, meshes, program link),
# warm-up (llvmpipe's JIT at the first draw) and the counted frames; the
# rest of the children's time is Valgrind's start-up and exit, the
# parent's reading of the dumps, and a child idle after its share.  Times
# are wall times under Valgrind, only as good as the machine was quiet (the
# load average is printed).
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
"$BIN" run "$SWEEP" --out "$OUT/with" --seed 1 2>"$OUT/with.log" >/dev/null
t1=$(date +%s.%N)
"$BIN" run "$OUT/plain.yaml" --out "$OUT/without" --seed 1 --quiet
t2=$(date +%s.%N)
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$OUT/with" "$t0" "$t1" "$t2" <<'PY'
import glob, re, sys
root, t0, t1, t2 = sys.argv[1], *map(float, sys.argv[2:])
m = re.search(r"instructions counted in ([\d.]+) s", open(f"{root}/../with.log").read())
pass_s = float(m.group(1)) if m else (t1 - t0) - (t2 - t1)
ctx = prep = warm = count = 0.0
n = 0
logs = glob.glob(f"{root}/2*/callgrind/child*.log")   # the run directory (not the latest link); one per child
for log in logs:
    for line in open(log, errors="replace"):
        m = re.search(r"instructions split: context ([\d.]+) ms", line)
        if m:
            ctx += float(m.group(1)) / 1e3
        m = re.search(r"prepare ([\d.]+) ms, warm-up ([\d.]+) ms, counted ([\d.]+) ms", line)
        if m:
            n += 1
            prep += float(m.group(1)) / 1e3; warm += float(m.group(2)) / 1e3; count += float(m.group(3)) / 1e3
jobs = max(len(logs), 1)
busy = pass_s * jobs                     # child-seconds: the pass's wall time on each child
rest = busy - ctx - prep - warm - count
print(f"run with Instructions {t1 - t0:.1f} s, without {t2 - t1:.1f} s (x{(t1 - t0) / (t2 - t1):.2f}); "
      f"the pass {pass_s:.1f} s for {n} configurations in {jobs} children side by side")
print(f"  time of the children, summed ({busy:.1f} s):")
for what, s in (("Valgrind start-up/exit, reading dumps, idle (the rest)", rest), ("GL context", ctx),
                ("prepare: maps, meshes, program link", prep), ("warm-up: first draw's JIT", warm),
                ("counted frames", count)):
    print(f"  {what:54} {s:7.1f} s  {100 * s / busy if busy > 0 else 0:5.1f} %")
if n:
    print(f"  per configuration: {busy / n:.1f} s in a child, {pass_s / n:.1f} s of the pass")
PY
