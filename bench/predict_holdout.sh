#!/usr/bin/env bash
# bench/predict_holdout.sh: `dmbench predict` on sweeps it was not fitted
# on (docs/models.md, "Prediction: held-out sweeps").  Each pair of
# bench/holdout/ is a training sweep NAME_fit.yaml and a target
# NAME_new.yaml with other resolutions, step counts and tessellation levels
# (up to 1.5x the highest fitted).  Measures both (RUNS times each,
# alternating; default 1) unless HOLDOUT_RUNS names a directory that holds
# them (NAME_fit/ and NAME_new/ output roots, NAME_fit2/ ... for more runs),
# predicts each target from its training runs pooled, and prints per
# configuration the Instructions and WallTime errors against the target's
# measured values (WallTime: the mean of its runs), whether the measured
# value lies in the prediction interval, the way predict chose, and per
# pair and over all: the worst errors and the interval coverage (as
# measured, and with each pair's common mode -- the whole target run
# against the fit run -- divided out), and the WallTime targets in the
# fitted range within 15 %, over it, or too noisy to judge (the measured
# value's own CI wider than that).
# Usage: bench/predict_holdout.sh [PAIR...]   (default: every pair; DMBENCH: the binary)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
B=${DMBENCH:-$here/build/dmbench}
runs=${RUNS:-1}
dir=${HOLDOUT_RUNS:-}
pairs=("$@")
[ ${#pairs[@]} -gt 0 ] || pairs=($(cd "$here/bench/holdout" && ls *_fit.yaml | sed 's/_fit.yaml$//'))
if [ -z "$dir" ]; then
  dir=$(mktemp -d)
  for p in "${pairs[@]}"; do
    for i in $(seq 1 "$runs"); do
      sfx=$([ "$i" = 1 ] && echo "" || echo "$i")
      for s in fit new; do
        t0=$(date +%s)
        "$B" run "$here/bench/holdout/${p}_$s.yaml" --out "$dir/${p}_$s$sfx" --seed "$i" --quiet
        echo "measured $p $s run $i: $(( $(date +%s) - t0 )) s, load $(cut -d' ' -f1-3 /proc/loadavg)"
      done
    done
  done
fi
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg); runs in $dir"
summary=$(mktemp)
for p in "${pairs[@]}"; do
  fit=$(ls -d "$dir/${p}_fit"*/latest | paste -sd,); new=$(ls -d "$dir/${p}_new"*/latest | paste -sd,)
  "$B" predict "$here/bench/holdout/${p}_new.yaml" --from "$fit" --json > "$dir/$p.json"
  "$B" predict "$here/bench/holdout/${p}_new.yaml" --from "$fit" > "$dir/$p.txt"
  echo; echo "== pair $p: fitted on $fit"
  sed -n '/^held-out error of WallTime/,$p' "$dir/$p.txt"
  python3 - "$dir/$p.json" "$new" "$p" "$summary" <<'PY'
import json, math, statistics, sys
pred = json.load(open(sys.argv[1]))["predictions"]
news = [json.load(open(d + "/results.json")) for d in sys.argv[2].split(",")]
pair, summary = sys.argv[3], sys.argv[4]
def val(c, n):
    x = c["counters"].get(n, {})
    return x.get("median", x.get("value"))
meas = {}
for j in news:
    for c in j["configs"]:
        if c.get("status", "ok") == "ok":
            meas.setdefault(c["key"], []).append(c)
rows, worst_i, worst_w, cov, tot, ratios, ivs = [], 0.0, 0.0, [0, 0], [0, 0], [], []
unav, calib = [0, 0], {}
# The 15 % target on WallTime (issue 49) is judged where the target's
# stage parts lie in the fitted range, and only where the measured value
# can tell: a target whose own 95 % CI, in any of its runs, is wider than
# +-15 % (llvmpipe's small frames on two cores can be bimodal: 3.5 and 5.2
# ms in one run) is "noisy", said so, and counted apart.
TARGET = 15.0
judged = {"within": 0, "over": 0, "noisy": 0}
def meas_ci(cs):
    """The widest relative half-width of the measured WallTime's 95 % CI over the runs."""
    w = 0.0
    for c in cs:
        x = c["counters"].get("WallTime", {})
        ci, m = x.get("ci95"), x.get("median")
        if isinstance(ci, list) and m:
            w = max(w, 100 * (ci[1] - ci[0]) / 2 / m)
    return w
print(f"| configuration | Instructions error | in | WallTime predicted / measured ms (CI) | error | in | way |")
print("|---|---|---|---|---|---|---|")
for p in pred:
    cs = meas.get(p["key"])
    if not p["predicted"] or not cs:
        print(f"| {p['label']} | not predicted: {p.get('reason', 'not measured')} |||||")
        continue
    ins, wt = p["counters"]["Instructions"], p["counters"]["WallTime"]
    mi = val(cs[0], "Instructions")
    mw = statistics.mean(val(c, "WallTime") for c in cs)
    ei = 100 * (ins["value"] / mi - 1)
    worst_i = max(worst_i, abs(ei))
    def inside(v, m):
        iv = v.get("interval")
        return "-" if not isinstance(iv, list) else ("in" if iv[0] <= m <= iv[1] else "OUT")
    ii = inside(ins, mi)
    if "value" in wt:
        ew = 100 * (wt["value"] / mw - 1)
        ratios.append((mw / wt["value"], wt["value"], mw))
        worst_w = max(worst_w, abs(ew))
        iw = inside(wt, mw)
        if isinstance(wt.get("interval"), list):
            ivs.append((wt["interval"], mw))
        wid = f" ×/÷{wt['interval'][1] / wt['value']:.2f}" if isinstance(wt.get("interval"), list) else ""
        mci = meas_ci(cs)
        verdict = ""
        if not p.get("extrapolation"):
            v = "noisy" if mci > TARGET else "within" if abs(ew) <= TARGET else "over"
            judged[v] += 1
            verdict = {"within": "", "over": " (over 15 %)", "noisy": " (too noisy to judge)"}[v]
        wtext = f"{wt['value'] / 1e6:.2f} / {mw / 1e6:.2f} (±{mci:.0f} %) | {ew:+.1f} %{verdict} | {iw}{wid}"
        way = wt.get("model", "") + (" (override)" if wt.get("model_override") else "")
    else:
        iw, wtext, way = "-", f"unavailable / {mw / 1e6:.2f} | - | -", "unavailable: " + wt.get("unavailable", "")
    for k, x in enumerate((ii, iw)):
        tot[k] += x != "-"
        cov[k] += x == "in"
        unav[k] += x == "-"
    calib[p.get("interval_calibration", "?")] = calib.get(p.get("interval_calibration", "?"), 0) + 1
    ex = p.get("extrapolation")
    label = p["label"] + (f" (extrapolated {ex['factor']:.1f}x {ex['stage']})" if ex else "")
    iwid = f" ±{100 * (ins['interval'][1] / ins['value'] - 1):.1f} %" if isinstance(ins.get("interval"), list) else ""
    print(f"| {label} | {ei:+.2f} % | {ii}{iwid} | {wtext} | {way} |")
print(f"pair {pair}: worst Instructions {worst_i:.2f} %, worst WallTime {worst_w:.1f} %, "
      f"intervals holding the measured value: Instructions {cov[0]}/{tot[0]}, WallTime {cov[1]}/{tot[1]}"
      f" (unavailable: Instructions {unav[0]}, WallTime {unav[1]}); calibration: "
      + ", ".join(f"{k} {v}" for k, v in sorted(calib.items())))
print(f"pair {pair}: WallTime in the fitted range: {judged['within']} within {TARGET:.0f} %, "
      f"{judged['over']} over, {judged['noisy']} too noisy to judge (a measured 95 % CI wider than "
      f"±{TARGET:.0f} %)")
# The common mode: the median configuration's measured over predicted
# WallTime.  A whole run moves against another with the machine's load
# (every configuration alike); the errors with it divided out are the
# model's share.
# The intervals' coverage with the common mode divided out too: whether
# each interval holds the measured value over the common mode, i.e. the
# model's own error against the shift of the whole run.
cov_cm = 0
if ratios:
    cm = statistics.median(r[0] for r in ratios)
    rest = max(abs(100 * (p * cm / m - 1)) for _, p, m in ratios)
    cov_cm = sum(1 for iv, m in ivs if iv[0] <= m / cm <= iv[1])
    print(f"pair {pair}: common mode x{cm:.3f} (measured / predicted, median configuration); "
          f"with it divided out the worst WallTime error is {rest:.1f} % and the intervals hold "
          f"{cov_cm}/{len(ivs)}")
with open(summary, "a") as f:
    f.write(f"{pair} {worst_i} {worst_w} {cov[0]} {tot[0]} {cov[1]} {tot[1]} {cov_cm} {tot[1]} "
            f"{judged['within']} {judged['over']} {judged['noisy']}\n")
PY
done
python3 - "$summary" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1])]
def cov(i):
    c, t = sum(int(r[i]) for r in rows), sum(int(r[i + 1]) for r in rows)
    return f"{c}/{t}" + (f" = {100 * c / t:.0f} %" if t else "")
def cov_all(*cols):
    c = sum(int(r[i]) for r in rows for i in cols[::2])
    t = sum(int(r[i]) for r in rows for i in cols[1::2])
    return f"{c}/{t}" + (f" = {100 * c / t:.0f} %" if t else "") + (" (target 90 %)" if t else "")
print(f"\nall pairs: worst Instructions {max(float(r[1]) for r in rows):.2f} %, worst WallTime "
      f"{max(float(r[2]) for r in rows):.1f} %; interval coverage: Instructions {cov(3)}, WallTime {cov(5)}, "
      f"WallTime with each pair's common mode divided out {cov(7)}")
print(f"interval coverage over all target configurations of the bench: {cov_all(3, 4, 5, 6)}; "
      f"with the common mode divided out {cov_all(3, 4, 7, 8)}")
w, o, n = (sum(int(r[i]) for r in rows) for i in (9, 10, 11))
print(f"WallTime in the fitted range (target: within 15 %): {w} within, {o} over, {n} too noisy to judge")
PY
rm -f "$summary"
