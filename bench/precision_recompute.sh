#!/usr/bin/env bash
# bench/precision_recompute.sh BIN DIR [RUNS] [OUT] — the drift correction of
# stored runs recomputed with BIN's code, timing nothing (docs/measurement.md,
# "Between runs").  DIR holds run-1 … run-RUNS (default 4) as
# bench/precision.sh leaves them; each is merged alone (`BIN merge`, which
# removes the drift again from the stored samples and rounds) into
# OUT/run-K (default a fresh directory), and the results.json files are read.
# It prints, per run, the WallTime configurations within ±3 % raw, corrected
# within the run and corrected between runs, and each scene's uncertainty of
# the run's median speed; for each pair of consecutive runs how many
# configurations' medians agree within their CIs (the CIs overlap), raw,
# with the within-run corrected CI and with the between-run one; and per
# scene the common factor (median log ratio of the corrected medians), how
# far the configurations spread around it, and how many agree once it is
# divided out.  It asserts only that every merge wrote WallTime for every
# configuration.
set -euo pipefail
BIN=${1:?usage: bench/precision_recompute.sh BIN DIR [RUNS] [OUT]}
DIR=${2:?usage: bench/precision_recompute.sh BIN DIR [RUNS] [OUT]}
RUNS=${3:-4}
OUT=${4:-$(mktemp -d /tmp/dmbench-recompute.XXXXXX)}
for k in $(seq 1 "$RUNS"); do
    "$BIN" merge "$OUT/run-$k" "$DIR/run-$k/latest" > /dev/null
done
python3 - "$OUT" "$RUNS" <<'PY'
import json, math, os, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])

def load(k):
    j = json.load(open(os.path.join(out, f"run-{k}", "latest", "results.json")))
    cfg = {}
    for c in j["configs"]:
        w = c.get("counters", {}).get("WallTime")
        if not w or "median" not in w:
            continue
        raw = (w["median"], *w["ci95"])
        cor = w.get("corrected")
        within = (cor["median"], *cor["ci95"]) if cor else raw
        between = (cor["median"], *cor["ci95_between_runs"]) if cor and cor.get("ci95_between_runs") else within
        cfg[c["key"]] = dict(scene=c["scene"], raw=raw, within=within, between=between)
    assert cfg, f"run {k}: no WallTime"
    ref = {s["scene"]: s.get("reference_spread") for s in j["precision"]["scenes"]}
    return cfg, ref

hw = lambda t: (t[2] - t[1]) / 2 / t[0]
overlap = lambda a, b: a[1] <= b[2] and b[1] <= a[2]
pct = lambda v: "unavailable" if v is None else f"{100 * v:.2f} %"
data = [load(k) for k in range(1, runs + 1)]
print("| run | raw within ±3 % | corrected, within-run CI | corrected, between-run CI "
      "| median half-width raw / within / between | median speed known to (per scene) |")
print("|---|---|---|---|---|---|")
for k, (cfg, ref) in enumerate(data, 1):
    v = list(cfg.values())
    count = lambda f: sum(hw(x[f]) <= 0.03 for x in v)
    med = lambda f: 100 * statistics.median(hw(x[f]) for x in v)
    print(f"| {k} | {count('raw')} of {len(v)} | {count('within')} | {count('between')} "
          f"| {med('raw'):.2f} / {med('within'):.2f} / {med('between'):.2f} % "
          f"| {', '.join('±' + pct(ref[s]) for s in sorted(ref))} |")
total = [0, 0, 0, 0]
for k in range(1, runs):
    a, b = data[k - 1][0], data[k][0]
    keys = [x for x in a if x in b]
    agree = [sum(overlap(a[x][f], b[x][f]) for x in keys) for f in ("raw", "within", "between")]
    total = [t + n for t, n in zip(total, agree + [len(keys)])]
    print(f"runs {k} and {k + 1}: medians agree within their CIs for {agree[0]} of {len(keys)} raw, "
          f"{agree[1]} corrected (within-run CI), {agree[2]} corrected (between-run CI)")
    for s in sorted({a[x]["scene"] for x in keys}):
        ks = [x for x in keys if a[x]["scene"] == s]
        lr = [math.log(b[x]["within"][0] / a[x]["within"][0]) for x in ks]
        f = statistics.median(lr)
        sd = 1.4826 * statistics.median(abs(v - f) for v in lr)
        rest = sum(overlap(a[x]["within"], tuple(t / math.exp(f) for t in b[x]["within"])) for x in ks)
        print(f"    {s}: common factor {100 * f:+.2f} %, configurations around it ±{100 * sd:.2f} %, "
              f"{rest} of {len(ks)} agree (within-run CI) once it is divided out")
if runs > 1:
    print(f"all pairs: {total[0]} of {total[3]} raw, {total[1]} corrected within-run, {total[2]} corrected between-run")
PY
echo "output: $OUT"
