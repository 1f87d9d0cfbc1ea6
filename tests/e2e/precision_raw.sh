#!/usr/bin/env bash
# End to end (issue 50, bad input): when the machine's drift cannot be
# measured — here a scene of two configurations, too few for a round's
# common mode — the run goes on with the raw figures only and says why:
# in the terminal, in summary.md and report.html (the scene and its
# reason under the noise floor), in results.json (the scene's record, no
# corrected figures) and results.csv (drift_correction gives the reason);
# the answer still picks from the raw figures, and nothing says the
# figures were corrected.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
cat > "$OUT/two.yaml" <<'YAML'
name: e2e-raw-only
resolution: [48, 27]
measure:
  warmup_frames: 2
  frames_per_sample: 2
  min_sample_ms: 2
  samples: { min: 3, max: 5, target_ci: 0.5 }
  max_seconds: 1
  counters: [WallTime]
sweep:
  mesh: [plane]
  technique: [normal, bump]
YAML
"$BIN" run "$OUT/two.yaml" --out "$OUT/r" 2> "$OUT/log" > "$OUT/answer"
sed -i ':a;N;$!ba;s/\n    */ /g' "$OUT/log"   # join wrapped lines
WHY="fewer than 3 configurations with samples in the scene: no common mode to measure; raw figures only"
grep -qF "dmbench: scene plane@48x27: $WHY" "$OUT/log" || { cat "$OUT/log"; exit 1; }
grep -q "[0-2] of 2 with the machine's drift removed (0 of 1 scenes corrected)" "$OUT/log"
grep -q "pick " "$OUT/answer"
if grep -q "disagree" "$OUT/answer"; then echo "a raw-only scene cannot disagree"; exit 1; fi
RUN="$OUT/r/latest"
grep -qF "  - plane 48×27: $WHY" "$RUN/summary.md"
grep -q "drift was removed in 0 of 1 scenes" "$RUN/summary.md"
test "$(grep -c '| raw only |' "$RUN/summary.md")" -eq 2
grep -qF "plane 48×27: $WHY" "$RUN/report.html"
if grep -q 'class="corr"' "$RUN/report.html"; then echo "corrected figures in a raw-only report"; exit 1; fi
python3 - "$RUN" "$WHY" <<'PY'
import csv, json, os, sys
run, why = sys.argv[1], sys.argv[2]
j = json.load(open(os.path.join(run, "results.json")))
p = j["precision"]
assert p["noise_floor"] > 0 and abs(p["resolvable"] / p["noise_floor"] - 2 ** 0.5) < 1e-12, p
assert [(s["scene"], s["corrected"], s["reason"]) for s in p["scenes"]] == [("plane@48x27", False, why)], p
for c in j["configs"]:
    w = c["counters"]["WallTime"]
    assert w["corrected"] is None and w["ci95"][0] <= w["median"] <= w["ci95"][1], w
rows = list(csv.DictReader(open(os.path.join(run, "results.csv"))))
assert len(rows) == 2 and all(r["drift_correction"] == why and r["WallTime_corr_median_ms"] == "" for r in rows), rows
print("raw only:", why)
PY
