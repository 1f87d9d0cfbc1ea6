#!/usr/bin/env bash
# bench/stages.sh [RUN_DIR]: where the default sweep's instructions go and
# what the models predict.  Runs bench/stages_default.yaml (the default
# sweep with the stage counters, reduced: see its header) unless a run
# directory is given, then prints
#  - the stage shares per technique (median over its configurations),
#  - the models' CV-MAPE: pipeline-linear on WallTime (before), and
#    stage-instructions on Instructions per variant, the three per-stage
#    models on their stage counters and
#    time-from-instructions, time-from-stages and the three stage-time
#    models (after), and the held-out error of each variant's Instructions
#    predicted by `dmbench predict` (the stage models summed, or
#    stage-instructions, whichever predicted better) and of WallTime,
#  - the cost of the stage windows in the counting child (its log).
# Usage: bench/stages.sh [RUN_DIR]   (DMBENCH: the binary, default build/dmbench)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
B=${DMBENCH:-$here/build/dmbench}
run=${1:-}
if [ -z "$run" ]; then
  out=$(mktemp -d)
  echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
  t0=$(date +%s)
  "$B" run "$here/bench/stages_default.yaml" --out "$out" --seed 1 --quiet
  echo "run: $(( $(date +%s) - t0 )) s, load after: $(cut -d' ' -f1-3 /proc/loadavg)"
  run=$out/latest
fi
python3 - "$run/results.json" <<'PY'
import json, statistics, sys
j = json.load(open(sys.argv[1]))
by = {}
for c in j["configs"]:
    g = {n: c["counters"].get(n, {}) for n in ("GeometryInstructions", "RasterInstructions", "FragmentInstructions")}
    if c["status"] != "ok" or any("unavailable" in v or not v for v in g.values()):
        continue
    parts = [v.get("median", v.get("value")) for v in g.values()]
    by.setdefault(c["params"]["technique"], []).append([p / sum(parts) for p in parts])
print("stage shares per technique (median over its configurations; geometry / raster / fragment):")
for t, s in by.items():
    m = [100 * statistics.median(x[k] for x in s) for k in range(3)]
    print(f"  {t:20s} geometry {m[0]:5.1f} %  raster {m[1]:5.1f} %  fragment {m[2]:5.1f} %  ({len(s)} configurations)")
PY
for m in "pipeline-linear" "stage-instructions" "geometry-instructions" "raster-instructions" \
         "fragment-instructions" "fragment-trips" "time-from-instructions" "time-from-stages" \
         "geometry-time" "raster-time" "fragment-time"; do
  echo "== fit --model $m"
  "$B" fit "$run" --model "$m" 2>/dev/null | grep -E "^model|CV-MAPE" | sed 's/^/  /' || true
done
echo "== predict: held-out error of Instructions per variant, and of WallTime"
"$B" predict "$here/bench/stages_default.yaml" --from "$run" 2>/dev/null | sed -n '/^held-out error/,$p' || true
logs=$(ls "$run"/callgrind/child*.log 2>/dev/null)   # one per counting child
if [ -n "$logs" ]; then
  awk '/stage windows/ {s += $(NF-1)} /counted .* ms$/ {c += $(NF-1); w += $(NF-4); p += $(NF-7)}
       /context/ {x += $(NF-1)}
       END {printf "counting children: context %.1f s, prepare %.1f s, warm-up %.1f s, counted frames %.1f s, stage windows %.1f s (%.0f %% of the child)\n",
            x/1000, p/1000, w/1000, c/1000, s/1000, 100*s/(x+p+w+c+s)}' $logs
fi
