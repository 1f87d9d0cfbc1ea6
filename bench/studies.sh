#!/usr/bin/env bash
# Re-measures every study table (sweeps/s<N>-table*.yaml, s2-section*.yaml)
# and prints, per study, the published figures beside ours with a verdict,
# the run's date and the load average (docs/reproductions.md).
#
#   bench/studies.sh BIN OUT time [NAME...]
#                                     each sweep with its own measure
#                                     section: frame times, meaningful only
#                                     on a quiet machine (load printed)
#   bench/studies.sh BIN OUT counts [NAME...]
#                                     the same scenes with exact counters
#                                     only (pipeline statistics and the
#                                     instructions of one frame under
#                                     callgrind): the same on any load;
#                                     with STAGES=1 also the stage counters
#                                     (Geometry/Raster/FragmentInstructions:
#                                     four counted windows a sample instead
#                                     of one) and each row's stage shares
#
# NAME... limits the run to those sweeps (e.g. s4-table8-1-2), in that
# order; by default every table sweep and s1-fig28 (S1's chart without
# published values: measured, no verdict).
# Resumable: a sweep whose OUT/MODE/NAME/DONE exists is not run again; an
# interrupted one continues with `dmbench run --resume`.  Running it again
# with the same OUT only prints.  Verdict rule (the reports' own): a row
# agrees when both ratios to the baseline point the same way (slower by more
# than 5 %, faster by more than 5 %, or both within ±5 %) and are within a
# factor of 2; in counts mode the measured ratio is of instructions per
# frame, which on llvmpipe (one core, LP_NUM_THREADS=0) tracks frame time.
set -euo pipefail
BIN=${1:?usage: bench/studies.sh path/to/dmbench OUT time|counts}
OUT=${2:?usage: bench/studies.sh path/to/dmbench OUT time|counts}
MODE=${3:?usage: bench/studies.sh path/to/dmbench OUT time|counts}
case "$MODE" in time|counts) ;; *) echo "bench/studies.sh: mode '$MODE': expected time or counts" >&2; exit 2 ;; esac
HERE=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$OUT/$MODE"
shift 3
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for f in "$HERE"/sweeps/s[1-4]-table*.yaml "$HERE"/sweeps/s2-section*.yaml "$HERE"/sweeps/s1-fig28.yaml; do
    names+=("$(basename "$f" .yaml)")
  done
fi

# counts mode: the sweep with one sample of exact counters and no quality pass
counts_sweep() {   # SRC DST
  python3 - "$1" "$2" "${STAGES:-0}" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
stages = ",\n             GeometryInstructions, RasterInstructions, FragmentInstructions" if sys.argv[3] == "1" else ""
s = re.sub(r"^measure:\n(?:  .*\n)+", "measure:\n  warmup_frames: 1\n  frames_per_sample: 1\n"
           "  samples: { min: 2, max: 2, target_ci: 50% }\n  max_seconds: 1\n"
           "  counters: [VSInvocations, TESInvocations, ClippingOutputPrimitives, SamplesPassed,\n"
           "             Instructions" + stages + "]\n", s, flags=re.M)
s = re.sub(r"^quality:.*\n", "", s, flags=re.M)
open(sys.argv[2], "w").write(s)
PY
}

for name in "${names[@]}"; do
  f="$HERE/sweeps/$name.yaml"
  [ -f "$f" ] || { echo "bench/studies.sh: no sweep $f" >&2; exit 2; }
  dir="$OUT/$MODE/$name"
  [ -e "$dir/DONE" ] && continue
  mkdir -p "$dir"
  sweep=$f
  if [ "$MODE" = counts ]; then
    sweep="$dir/$name.yaml"
    counts_sweep "$f" "$sweep"
  fi
  resume=()
  [ -e "$dir/dmbench.sqlite" ] && resume=(--resume)
  before=$(cut -d' ' -f1-3 /proc/loadavg)
  echo "$name: running ($MODE), load $before" >&2
  "$BIN" run "$sweep" --out "$dir" --seed 1 --quiet "${resume[@]}"
  echo "$(date -u +%Y-%m-%dT%H:%MZ) load before $before, after $(cut -d' ' -f1-3 /proc/loadavg)" > "$dir/DONE"
done

python3 - "$OUT/$MODE" "$MODE" <<'PY'
import glob, json, os, sys
root, mode = sys.argv[1], sys.argv[2]
metric = "WallTime" if mode == "time" else "Instructions"

def value(counters, name=None):
    c = counters.get(name or metric) or {}
    return c.get("median", c.get("value"))

def shares(counters):   # "geometry 9 % raster 4 % fragment 87 %", or "" without the stage counters
    v = [value(counters, n) for n in ("GeometryInstructions", "RasterInstructions", "FragmentInstructions")]
    if mode != "counts" or None in v or sum(v) <= 0:
        return ""
    return "  geometry %.1f %% raster %.1f %% fragment %.1f %%" % tuple(100 * x / sum(v) for x in v)

def verdict(p, m):
    side = lambda r: 0 if abs(r - 1) <= 0.05 else (1 if r > 1 else -1)
    if side(p) != side(m):
        return "differs (direction)"
    return "agrees" if max(p, m) / min(p, m) <= 2 else "differs (x%.1f)" % (max(p, m) / min(p, m))

for d in sorted(glob.glob(os.path.join(root, "s*"))):
    latest = os.path.join(d, "latest")
    if not os.path.exists(latest):   # a sweep with `drivers:` runs each driver into d/DRIVER/
        found = sorted(glob.glob(os.path.join(d, "*", "latest")))
        latest = found[0] if found else latest
    pub_f, res_f = os.path.join(latest, "published.json"), os.path.join(latest, "results.json")
    if not os.path.exists(res_f):
        continue
    res = json.load(open(res_f))
    done = open(os.path.join(d, "DONE")).read().strip() if os.path.exists(os.path.join(d, "DONE")) else "unfinished"
    by_key = {c["key"]: c for c in res["configs"]}
    if not os.path.exists(pub_f):   # a study chart without published values
        print("\n%s — no published values; measured by %s, %s" % (os.path.basename(d), metric, done))
        for c in res["configs"]:
            m = value(c["counters"])
            print("  %-60s %s%s" % (c["label"][-60:], "%.0f" % m if m and mode == "counts"
                                    else "%.2f ms" % (m / 1e6) if m else "—", shares(c["counters"])))
        continue
    pub = json.load(open(pub_f))
    inv = pub["unit"] == "fps"
    vals = {v["label"]: v for v in pub["values"]}
    base = vals[pub["baseline"]]
    bm = value(by_key[base["key"]]["counters"]) if base["key"] in by_key else None
    print("\n%s — %s, %s (%s); measured by %s, %s" % (os.path.basename(d), pub["source"]["table"],
          pub["source"].get("gpu", ""), pub["unit"], metric, done))
    print("  %-44s %10s %8s %14s %8s  %s" % ("configuration", "published", "ratio", "measured", "ratio", "verdict"))
    for label, v in vals.items():
        pr = (base["value"] / v["value"]) if inv else (v["value"] / base["value"])
        c = by_key.get(v["key"])
        m = value(c["counters"]) if c else None
        mr = m / bm if m and bm else None
        shown = "%14.0f" % m if m and mode == "counts" else ("%11.2f ms" % (m / 1e6) if m else "%14s" % "—")
        ver = "baseline" if label == pub["baseline"] else (verdict(pr, mr) if mr else "no measurement")
        print("  %-44s %10g %8.3f %s %8s  %s%s" % (label[:44], v["value"], pr, shown,
              "%.3f" % mr if mr else "—", ver, shares(c["counters"]) if c else ""))
PY
