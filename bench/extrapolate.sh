#!/usr/bin/env bash
# bench/extrapolate.sh [FIT_RUN NEW_RUN]: the extrapolation target of the
# cost models (docs/models.md, "Prediction").  Measures
# bench/extrapolate_fit.yaml (two resolutions, three tessellation levels,
# two POM step counts, two meshes) and bench/extrapolate_new.yaml (a larger
# resolution, a level and a step count between and beyond, another mesh
# density), unless both run directories are given; predicts the second from
# the first with `dmbench predict` and prints predicted against measured
# Instructions and WallTime per configuration (and whether the measured
# value is inside the prediction interval), the load average with it.
# Usage: bench/extrapolate.sh [FIT_RUN NEW_RUN]   (DMBENCH: the binary)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
B=${DMBENCH:-$here/build/dmbench}
fit=${1:-}; new=${2:-}
if [ -z "$fit" ]; then
  out=$(mktemp -d)
  t0=$(date +%s)
  "$B" run "$here/bench/extrapolate_fit.yaml" --out "$out/fit" --seed 1 --quiet
  "$B" run "$here/bench/extrapolate_new.yaml" --out "$out/new" --seed 1 --quiet
  echo "two runs: $(( $(date +%s) - t0 )) s"
  fit=$out/fit/latest; new=$out/new/latest
fi
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
"$B" predict "$here/bench/extrapolate_new.yaml" --from "$fit" > "${TMPDIR:-/tmp}/extrapolate.pred"
python3 - "${TMPDIR:-/tmp}/extrapolate.pred" "$new/results.json" "$fit/results.json" <<'PY'
import json, re, statistics, sys
newj, fitj = json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
meas = {c["key"]: c for c in newj["configs"]}
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
    mi, mw = med(c, "Instructions"), med(c, "WallTime") / 1e6
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
def calib(j, k):
    e = j["run"]["environment"]
    return (float(e[f"calibration_{k}_ns_start"]) + float(e[f"calibration_{k}_ns_end"])) / 2
if ratios:
    cm = statistics.median(ratios)
    print(f"common mode: measured/predicted WallTime median x{cm:.3f}; the calibration "
          f"workload took x{calib(newj, 'cpu') / calib(fitj, 'cpu'):.3f} (CPU kernel) and "
          f"x{calib(newj, 'draw') / calib(fitj, 'draw'):.3f} (draw) of the fitted run's time in the new one")

print("\n".join(heldout))
PY
