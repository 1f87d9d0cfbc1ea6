#!/usr/bin/env bash
# bench/precision.sh BIN [RUNS] [OUT] — issue 50's targets on the default
# sweep (docs/measurement.md, "Drift removed"): runs `BIN run` (the default
# sweep) RUNS times (default 4) into OUT/run-K and prints, per run, how many
# configurations have a WallTime 95 % CI within ±3 %, raw and with the
# machine's drift removed, the median CI half-widths, the run's noise floor
# and smallest resolvable difference, its wall time and the load average
# before and after; then whether the runs name the same pick for every
# scene (from each run's answer, which reads the raw figures), and for each
# pair of consecutive runs how many configurations' medians agree within
# their CIs (the CIs overlap), raw, corrected with the within-run CI and
# corrected with the between-run CI (from results.json: the store keeps
# the within-run CI only).  The default run spends 60 s of extra rounds
# on the configurations short of their target (`dmbench run --help`);
# EXTRA=SEC in the environment runs each with `--extra-time SEC` instead
# (EXTRA=0: none); the runs' account of the extra rounds is printed, and
# `bench/precision_offline.py OUT/run-K/dmbench.sqlite` says why the
# configurations that missed did; each run's answer lines that say the raw and drift-corrected
# figures disagree are counted.  It measures; it asserts only that every
# run finished and stored WallTime for every configuration.
set -euo pipefail
BIN=${1:?usage: bench/precision.sh BIN [RUNS] [OUT]}
RUNS=${2:-4}
OUT=${3:-$(mktemp -d /tmp/dmbench-precision.XXXXXX)}
mkdir -p "$OUT"
for k in $(seq 1 "$RUNS"); do
    load0=$(cut -d' ' -f1 /proc/loadavg)
    t0=$(date +%s)
    "$BIN" run --out "$OUT/run-$k" ${EXTRA:+--extra-time "$EXTRA"} > "$OUT/answer-$k.txt" 2> "$OUT/log-$k.txt"
    t1=$(date +%s)
    load1=$(cut -d' ' -f1 /proc/loadavg)
    echo "$k $((t1 - t0)) $load0 $load1" >> "$OUT/times.txt"
    echo "run $k: $((t1 - t0)) s, load $load0 -> $load1" >&2
done
python3 - "$OUT" "$RUNS" <<'PY'
import json, os, re, sqlite3, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
times = {int(l.split()[0]): l.split()[1:] for l in open(os.path.join(out, "times.txt"))}
data = []
for k in range(1, runs + 1):
    db = sqlite3.connect(os.path.join(out, f"run-{k}", "dmbench.sqlite"))
    run = db.execute("SELECT id FROM runs ORDER BY started DESC LIMIT 1").fetchone()[0]
    rows = db.execute("SELECT c.key, c.scene, k.median, k.ci_lo, k.ci_hi, k.corrected, k.corr_median,"
                      " k.corr_ci_lo, k.corr_ci_hi FROM configs c JOIN counters k ON k.run=c.run AND"
                      " k.key=c.key AND k.name='WallTime' WHERE c.run=? AND c.status='ok'", (run,)).fetchall()
    assert rows, f"run {k}: no WallTime stored"
    # the between-run CI is in results.json only (the store keeps the within-run one)
    between = {}
    rj = os.path.join(out, f"run-{k}", "latest", "results.json")
    for c in json.load(open(rj))["configs"] if os.path.exists(rj) else []:
        w = (c.get("counters") or {}).get("WallTime") or {}
        b = (w.get("corrected") or {}).get("ci95_between_runs")
        if b:
            between[c["key"]] = (w["corrected"]["median"], b[0], b[1])
    cfg = {}
    for key, scene, m, lo, hi, corr, cm, clo, chi in rows:
        raw = (m, lo, hi)
        cor = (cm, clo, chi) if corr else raw
        cfg[key] = (scene, raw, cor, between.get(key, cor))
    data.append(cfg)
    # the answer's lines wrap at 100 columns, continuations four columns in
    answer = re.sub(r"\n    +", " ", open(os.path.join(out, f"answer-{k}.txt")).read())
    picks = dict(re.findall(r"^(\S.*?): .*?: pick (\S+)", answer, re.M))   # "…(default budget…): pick X"; a provisional budget says "where the pick is"
    prov = set(re.findall(r"^(\S.*?): Provisional", answer, re.M))
    data[-1] = (cfg, picks, prov)
hw = lambda t: (t[2] - t[1]) / 2 / t[0] if t[0] and t[1] is not None and t[2] is not None else float("inf")
print("| run | wall s | load before → after | configs | raw within ±3 % | corrected within ±3 % "
      "| median half-width raw | corrected | noise floor | resolvable |")
print("|---|---|---|---|---|---|---|---|---|---|")
for k, (cfg, picks, prov) in enumerate(data, 1):
    raw = [hw(v[1]) for v in cfg.values()]
    cor = [hw(v[2]) for v in cfg.values()]
    floor = statistics.median(cor)
    t = times[k]
    print(f"| {k} | {t[0]} | {t[1]} → {t[2]} | {len(cfg)} | {sum(h <= 0.03 for h in raw)} "
          f"({100 * sum(h <= 0.03 for h in raw) / len(cfg):.0f} %) | {sum(h <= 0.03 for h in cor)} "
          f"({100 * sum(h <= 0.03 for h in cor) / len(cfg):.0f} %) | {100 * statistics.median(raw):.2f} % "
          f"| {100 * statistics.median(cor):.2f} % | ±{100 * floor:.2f} % | {100 * 2 ** 0.5 * floor:.2f} % |")
scenes = sorted(set().union(*[set(p) for _, p, _ in data]))
agree = 0
for s in scenes:
    names = [p.get(s, "-") for _, p, _ in data]
    provisional = all(s in pv for _, _, pv in data)
    same = len(set(names)) == 1
    agree += same or provisional
    print(f"pick {s}: {' / '.join(names)}{'' if same else ' (differ' + (', all provisional)' if provisional else ')')}")
print(f"picks: {agree} of {len(scenes)} scenes the same in every run or provisional in all (answer from raw figures)")
for k in range(1, runs + 1):
    joined = re.sub(r"\n    +", " ", open(os.path.join(out, f"answer-{k}.txt")).read())
    print(f"run {k}: raw and drift-corrected figures disagree on {joined.count('figures disagree')} scene(s)")
def overlap(a, b):
    return a[1] is not None and b[1] is not None and a[1] <= b[2] and b[1] <= a[2]
for k in range(1, len(data)):
    a, b = data[k - 1][0], data[k][0]
    common = [key for key in a if key in b]
    r = sum(overlap(a[x][1], b[x][1]) for x in common)
    c = sum(overlap(a[x][2], b[x][2]) for x in common)
    bt = sum(overlap(a[x][3], b[x][3]) for x in common)
    print(f"runs {k} and {k + 1}: medians agree within their CIs for {r} of {len(common)} raw, "
          f"{c} of {len(common)} corrected (within-run CI), {bt} of {len(common)} corrected (between-run CI)")
PY
grep -h "^dmbench: \(precision\|noise floor\|the machine\|extra rounds\)" "$OUT"/log-*.txt
echo "output: $OUT"
