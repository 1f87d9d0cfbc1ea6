#!/usr/bin/env bash
# `dmbench predict` readable and scriptable (issue 46), in seconds: runs
# made without Valgrind are given exact Instructions (predict_fixture.py),
# then predict's table, --json and --csv are checked against each other:
#  - the one label form (two pom rows differ by steps=), within 100 columns,
#    counts in grouped digits, never nan or an exponent;
#  - a variant measured twice: its interval is "unavailable" with the real
#    cause (too few configurations), never "[nan, nan]" or "[0.000, nan]";
#    the stage shares name the missing stage counters once;
#  - --json and --csv carry the same fields: key, label, each counter with
#    its interval or the reason, the model, whether it extrapolates;
#  - --json's wall_time_ways: the way used has the lowest held-out error
#    (at most 50 %), every WallTime interval is a ratio around its value;
#  - --json with --csv is refused (exit 2).
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
sweep() {   # NAME TECHNIQUES STEPS RESOLUTIONS
  cat <<YAML
name: $1
measure:
  warmup_frames: 1
  frames_per_sample: 1
  samples: { min: 2, max: 2, target_ci: 50% }
  counters: [WallTime, VSInvocations, TESInvocations, ClippingOutputPrimitives, FSInvocations, SamplesPassed]
scene:
  camera: { distance: 3.0, azimuth: 30, elevation: 35, fov: 45 }
  mesh: cube
sweep:
  technique: [$2]
  steps: [$3]
  resolution: [$4]
YAML
}
sweep predict-cli-fit "normal, pom" "8, 16" '"32x32", "40x40", "48x48", "56x56", "64x64"' > "$OUT/fit.yaml"
sweep predict-cli-two "phong" "8" '"32x32", "64x64"' > "$OUT/two.yaml"
sweep predict-cli-new "normal, pom, phong, texture" "16, 24" '"96x96"' > "$OUT/new.yaml"
for r in fit two; do
  "$BIN" run "$OUT/$r.yaml" --out "$OUT/$r" --quiet
  python3 "$SRC/tests/cli/predict_fixture.py" "$OUT/$r/dmbench.sqlite" >/dev/null
done
# the same two runs, phong's with the stage counters: phong then has stage
# parts, and normal's and pom's stage shares say their variants' runs have
# none (not "the runs lack the stage counters": these runs have them)
cp -r "$OUT/two" "$OUT/two_st"
python3 "$SRC/tests/cli/predict_fixture.py" "$OUT/two_st/dmbench.sqlite" --stages >/dev/null
"$BIN" predict "$OUT/new.yaml" --from "$OUT/fit/latest,$OUT/two_st/latest" --json > "$OUT/stages.json"
python3 - "$OUT/stages.json" <<'PY' && pass=$((pass+1)) || fail=$((fail+1))
import json, sys
p = {x["label"]: x for x in json.load(open(sys.argv[1]))["predictions"]}
ph = p["cube 96×96 · phong"]["counters"]["GeometryInstructions"]
no = p["cube 96×96 · normal"]["counters"]["GeometryInstructions"].get("unavailable", "")
ok = "value" in ph and "the runs have no stage counters for variant 'normal" in no
print("stage shares:", ph, "/", no)
sys.exit(0 if ok else 1)
PY
from="$OUT/fit/latest,$OUT/two/latest"
"$BIN" predict "$OUT/new.yaml" --from "$from" > "$OUT/table.txt"
"$BIN" predict "$OUT/new.yaml" --from "$from" --json > "$OUT/pred.json"
"$BIN" predict "$OUT/new.yaml" --from "$from" --csv > "$OUT/pred.csv"
cat "$OUT/table.txt"
python3 - "$OUT" <<'PY'
import csv, json, os, re, sys
out = sys.argv[1]
table = open(os.path.join(out, "table.txt")).read()
j = json.load(open(os.path.join(out, "pred.json")))
rows = list(csv.DictReader(open(os.path.join(out, "pred.csv"))))
fails = []
def check(ok, what):
    if not ok:
        fails.append(what)
def grouped(v):
    s = "%d" % round(v)
    parts = []
    while s:
        parts.insert(0, s[-3:]); s = s[:-3]
    return "\u202f".join(parts) if len(parts) > 1 else parts[0]

P = j["predictions"]
check(len(P) == 5 and len(rows) == 5, "five configurations in --json and --csv")
by_label = {p["label"]: p for p in P}
for want in ("cube 96×96 · pom steps=16", "cube 96×96 · pom steps=24", "cube 96×96 · normal",
             "cube 96×96 · phong", "cube 96×96 · texture"):
    check(want in by_label, "label %r missing from --json: %s" % (want, sorted(by_label)))
    check(want in table, "label %r missing from the table" % want)
for line in table.splitlines():
    check(len(line) <= 100, "table line over 100 columns (%d): %r" % (len(line), line))
nokeys = re.sub(r"\b[0-9a-f]{16}\b", "KEY", table)
check(re.search(r"\bnan\b|\d[eE][+-]?\d", nokeys) is None, "nan or an exponent in the table")
check("[0.000, nan]" not in table and "[nan, nan]" not in table, "half or no interval printed")
# the variant measured twice: its interval is unavailable, with the cause
ph = by_label["cube 96×96 · phong"]
ins = ph["counters"]["Instructions"]
check(ph["predicted"] and ins["interval"] == "unavailable" and
      "measured 2 configurations" in ins["interval_reason"] and "too few" in ins["interval_reason"],
      "phong's Instructions interval: %s" % ins)
check(ph["counters"]["WallTime"]["interval"] == "unavailable" and ph["counters"]["WallTime"]["interval_reason"],
      "phong's WallTime interval: %s" % ph["counters"]["WallTime"])
check(re.search(r"Instructions\s+interval\s+unavailable:\s+the\s+runs\s+measured\s+2\s+configurations\s+of\s+"
                r"variant\s+'phong", table),
      "the table does not say why phong has no interval")
# stage counters the runs lack: named once, not on every row
check(table.count("the runs lack the stage counters") == 2,   # under the table, and the WallTime held-out line
      "the missing stage counters are not said exactly once under the table")
tx = by_label["cube 96×96 · texture"]
check(not tx["predicted"] and "never measured" in tx["reason"], "texture: %s" % tx)
check(re.search(r"never measured", table), "the table does not list texture as not predicted")
for p, r in zip(P, rows):
    check(p["key"] == r["key"] and p["label"] == r["label"], "CSV row order/labels: %s" % r)
    if not p["predicted"]:
        check(r["predicted"] == "no" and r["reason"] == p["reason"], "CSV reason of %s" % p["label"])
        continue
    c = p["counters"]
    i = c["Instructions"]
    check(abs(float(r["Instructions"]) - i["value"]) <= 1e-9 * i["value"], "CSV Instructions of %s" % p["label"])
    check(r["Instructions_model"] == i["model"] and i["model"] in ("stage-instructions", "stage models summed"),
          "model of %s: %s" % (p["label"], i.get("model")))
    check(c["WallTime"]["model"] == r["WallTime_model"], "WallTime model of %s" % p["label"])
    # the intervals' calibration: leave-one-out at values the runs measured,
    # else held-out groups or why not (docs/models.md, "Intervals")
    check(p["interval_calibration"] == r["interval_calibration"] and
          p.get("calibration_reason", "") == r["calibration_reason"] and
          p["interval_calibration"] in ("leave-one-out", "held-out groups", "leave-one-out, groups unavailable") and
          (p["interval_calibration"] == "leave-one-out") == ("calibration_reason" not in p),
          "calibration of %s: %s / %s" % (p["label"], p.get("interval_calibration"), r["interval_calibration"]))
    check(p["extrapolates"] is None and r["extrapolates"] == "unknown",
          "extrapolation is unknown without stage parts: %s / %s" % (p["extrapolates"], r["extrapolates"]))
    if isinstance(i["interval"], list):
        lo, hi = i["interval"]
        check(lo < i["value"] < hi and r["Instructions_lo"] and r["Instructions_unavailable"] == "",
              "interval of %s" % p["label"])
        pct = 100 * (hi - i["value"]) / i["value"]
        row = [l for l in table.splitlines() if p["key"] in l][0]
        check(grouped(i["value"]) in row and ("±%.1f %%" % pct) in row, "table row of %s: %r" % (p["label"], row))
    else:
        check(r["Instructions_lo"] == "" and r["Instructions_unavailable"] == i["interval_reason"],
              "CSV unavailable interval of %s" % p["label"])
    w = c["WallTime"]
    for s in ("GeometryInstructions", "RasterInstructions", "FragmentInstructions"):
        check("the runs lack the stage counters" in c[s].get("unavailable", ""), "%s of %s" % (s, p["label"]))
    check(r["stages_unavailable"] == c["GeometryInstructions"]["unavailable"], "CSV stages of %s" % p["label"])
# each way of predicting WallTime with its held-out error: the one used is
# the lowest at most 50 %, the others say why not (these runs lack the
# stage counters); every WallTime interval a ratio around its value
W = j["wall_time_ways"]
check([w["way"] for w in W] == ["stage times", "time-from-stages", "time-from-instructions"], "ways: %s" % W)
used = [w for w in W if w["used"]]
scored = [w for w in W if "heldout_mape" in w]
check(all("unavailable" in w for w in W if "heldout_mape" not in w), "a way with neither error nor reason: %s" % W)
check("the runs lack the stage counters" in W[0].get("unavailable", ""), "stage times: %s" % W[0])
if used:
    check(len(used) == 1 and used[0]["heldout_mape"] <= 50 and
          used[0]["heldout_mape"] == min(w["heldout_mape"] for w in scored), "the way used: %s" % W)
else:
    check(all(w["heldout_mape"] > 50 for w in scored), "no way used though one held out within 50 %%: %s" % W)
for p in P:
    w = p.get("counters", {}).get("WallTime", {})
    if isinstance(w.get("interval"), list):
        lo, hi = w["interval"]
        check(0 < lo < w["value"] < hi and abs(lo * hi / w["value"] ** 2 - 1) < 1e-9,
              "WallTime interval of %s not a ratio around its value: %s" % (p["label"], w))
    if p["predicted"] and "value" in w:
        check(w["model"] == used[0]["way"] if used else False, "WallTime of %s by %s" % (p["label"], w.get("model")))
if fails:
    print("\n".join("FAIL: " + f for f in fails)); sys.exit(1)
print("predict table, --json and --csv ok")
PY
expect_refused 2 "choose one output" -- "$BIN" predict "$OUT/new.yaml" --from "$from" --json --csv
tally
