#!/usr/bin/env bash
# bench/extrapolate.sh [FIT_RUN[,FIT_RUN...] NEW_RUN[,NEW_RUN...]]: the
# extrapolation target of the cost models (docs/models.md, "Prediction").
# Measures bench/extrapolate_fit.yaml (two resolutions, three tessellation
# levels, two POM step counts, two meshes) and bench/extrapolate_new.yaml (a
# larger resolution, a level and a step count between and beyond, another
# mesh density), RUNS times each (default 2), alternating, unless the run
# directories are given; predicts the second from the first runs pooled
# with `dmbench predict` and prints predicted against measured Instructions
# and WallTime per configuration (the mean over the new runs, and whether
# it is inside the prediction interval), the load average with it.  Several
# runs a side because a whole run moves against another by up to ~12 % on
# this machine (every configuration alike): one run a side measures that
# as much as the model.
# Usage: bench/extrapolate.sh [FIT_RUNS NEW_RUNS]   (DMBENCH: the binary; RUNS: runs a side)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
B=${DMBENCH:-$here/build/dmbench}
fit=${1:-}; new=${2:-}
if [ -z "$fit" ]; then
  out=$(mktemp -d)
  t0=$(date +%s)
  fit=""; new=""
  for i in $(seq 1 "${RUNS:-2}"); do
    "$B" run "$here/bench/extrapolate_fit.yaml" --out "$out/fit$i" --seed "$i" --quiet
    "$B" run "$here/bench/extrapolate_new.yaml" --out "$out/new$i" --seed "$i" --quiet
    fit="$fit${fit:+,}$out/fit$i/latest"; new="$new${new:+,}$out/new$i/latest"
  done
  echo "$(( 2 * ${RUNS:-2} )) runs: $(( $(date +%s) - t0 )) s"
fi
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
"$B" predict "$here/bench/extrapolate_new.yaml" --from "$fit" > "${TMPDIR:-/tmp}/extrapolate.pred"
python3 - "${TMPDIR:-/tmp}/extrapolate.pred" "$new" "$fit" <<'PY'
import json, re, statistics, sys
newj = [json.load(open(d + "/results.json")) for d in sys.argv[2].split(",")]
fitj = [json.load(open(d + "/results.json")) for d in sys.argv[3].split(",")]
meas = {c["key"]: c for c in newj[0]["configs"]}
# each new configuration's WallTime median in every new run
walls = {}
for j in newj:
    for c in j["configs"]:
        w = c["counters"].get("WallTime", {})
        walls.setdefault(c["key"], []).append(w.get("median", w.get("value")))
ratios = []
def med(c, n):
    x = c["counters"].get(n, {})
    return x.get("median", x.get("value"))
print(f"{'configuration':44s} {'Instructions pred/meas':>28s} {'err':>7s} {'WallTime pred/meas ms':>24s} {'err':>7s}     beyond the fit (stage, times its largest)")
worst = [0, 0]
section = "table"
heldout = []
for l in open(sys.argv[1]).read().splitlines():
    f = l.split()
    if l.startswith("not predicted"):
        section = "unpredicted"
    elif l.startswith("held-out error"):
        section = "heldout"
    if section == "heldout":
        heldout.append(l)
        continue
    if l.startswith(" ") or not f or f[0] not in meas:
        if l.startswith(" "):
            print("not predicted:", l.strip())
        continue
    c = meas[f[0]]
    p = c["params"]
    name = f"{p['technique']} {p.get('resolution')} L={p.get('tess_level','-')} steps={p.get('steps','-')} d={p.get('mesh_density','0')}"
    pi_ = re.search(r"(\S+) \[(\S+), (\S+)\]", l)
    pi, ilo, ihi = (float(x) for x in pi_.groups())
    wt = re.search(r"WallTime (\S+) ms \[(\S+), (\S+)\]", l)
    mi, mw = med(c, "Instructions"), statistics.mean(walls[f[0]]) / 1e6   # WallTime: the new runs' mean
    ei = 100 * (pi / mi - 1)
    ew = 100 * (float(wt.group(1)) / mw - 1) if wt else float("nan")
    worst = [max(worst[0], abs(ei)), max(worst[1], abs(ew))]
    if wt:
        ratios.append(mw / float(wt.group(1)))
    # "in"/"OUT": the measured value inside the prediction interval or not
    ii = "in" if ilo <= mi <= ihi else "OUT"
    iw = ("in" if float(wt.group(2)) <= mw <= float(wt.group(3)) else "OUT") if wt else "-"
    ex = re.search(r"\(extrapolated: (\S+) (\S+) x", l)
    beyond = f"{ex.group(1)} {float(ex.group(2)):.3g}x" if ex else ""
    print(f"{name:44s} {pi:13.0f} / {mi:13.0f} {ei:+6.2f}% {ii:3s} {float(wt.group(1)) if wt else float('nan'):10.3f} / {mw:10.3f} {ew:+6.1f}% {iw:3s} {beyond}")
print(f"worst: Instructions {worst[0]:.2f} %, WallTime {worst[1]:.1f} % (in/OUT: the measured value inside the prediction interval)")
# a shift common to every configuration is the machine's speed between the
# two runs, not the model: the calibration workload of each run beside it
def calib(js, k):
    return statistics.mean((float(j["run"]["environment"][f"calibration_{k}_ns_start"]) +
                            float(j["run"]["environment"][f"calibration_{k}_ns_end"])) / 2 for j in js)
if ratios:
    cm = statistics.median(ratios)
    print(f"common mode: measured/predicted WallTime median x{cm:.3f}; the calibration "
          f"workload took x{calib(newj, 'cpu') / calib(fitj, 'cpu'):.3f} (CPU kernel) and "
          f"x{calib(newj, 'draw') / calib(fitj, 'draw'):.3f} (draw) of the fitted run's time in the new one")

if len(newj) > 1:   # how far the new runs themselves stand apart, per configuration
    spread = [100 * (max(v) / min(v) - 1) for v in walls.values() if len(v) > 1 and min(v) > 0]
    print(f"the {len(newj)} new runs among themselves: WallTime max/min {statistics.median(spread):.1f} % "
          f"(median configuration), {max(spread):.1f} % (largest)")
print("\n".join(heldout))
PY
