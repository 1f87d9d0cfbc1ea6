#!/usr/bin/env bash
# End to end: `dmbench run` of a tiny sweep writes results.json with the
# contract's keys, report.html, results.csv, summary.md and the images; the
# store holds the run; `dmbench report` rebuilds the files.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"

# dmbench info finds a GL 4.5 context and decides the timer by measurement.
"$BIN" info --json > "$OUT/info.json"
"$BIN" list counters --json > "$OUT/counters.json"
python3 - "$OUT/info.json" "$OUT/counters.json" <<'PY'
import json, sys
i = json.load(open(sys.argv[1]))
assert i["environment"]["gl_version"].startswith("4.5"), i["environment"]["gl_version"]
assert i["timer"]["verdict"] in ("partial", "full"), i["timer"]
assert 0 <= i["timer"]["gpu_time_coverage"] and i["timer"]["wall_ns"] > 0
assert i["extensions"]["GL_ARB_pipeline_statistics_query"] is True
c = {x["name"]: x for x in json.load(open(sys.argv[2]))}
assert c["VSInvocations"]["deterministic"] and c["VSInvocations"]["available"]
assert c["ShadingEfficiency"]["formula"] == "SamplesPassed / FSInvocations"
print("info:", i["timer"]["verdict"], "coverage %.4f" % i["timer"]["gpu_time_coverage"])
PY

"$BIN" run "$SRC/tests/e2e/tiny.yaml" --out "$OUT" --quiet
RUN="$OUT/latest"
for f in report.html results.json results.csv summary.md; do
  test -s "$RUN/$f" || { echo "missing $f"; exit 1; }
done
test -s "$OUT/dmbench.sqlite"

python3 - "$RUN" <<'PY'
import json, os, sys
run = sys.argv[1]
j = json.load(open(os.path.join(run, "results.json")))
for k in ("id", "sweep", "started", "environment", "timer"):
    assert k in j["run"], k
for k in ("renderer", "gl_version", "lp_num_threads", "cpu", "fingerprint"):
    assert k in j["run"]["environment"], k
# the calibration workload, timed at the run's start and end (nanoseconds)
for piece in ("cpu", "draw"):
    for which in ("start", "end"):
        v = float(j["run"]["environment"]["calibration_%s_ns_%s" % (piece, which)])
        assert 1e4 < v < 1e10, (piece, which, v)
assert j["run"]["sweep"] == "e2e-tiny"
assert j["run"]["timer"]["verdict"] in ("partial", "full", "unavailable")
# 2 meshes x 2 resolutions; tess_level is folded (normal does not read it)
assert len(j["configs"]) == 4, len(j["configs"])
for c in j["configs"]:
    assert c["status"] == "ok", (c["key"], c.get("reason"), c.get("log"))
    assert len(c["key"]) == 16
    assert "tess_level" not in c["params"]
    wt = c["counters"]["WallTime"]
    assert wt["unit"] == "ns" and wt["median"] > 0 and len(wt["samples"]) >= 3
    assert wt["ci95"][0] <= wt["median"] <= wt["ci95"][1]
    sp = c["counters"]["SamplesPassed"]
    w, h = map(int, c["params"]["resolution"].split("x"))
    assert 0 < sp["value"] <= w * h, sp
    # derived counters are formulas over the measured values (docs/counters.md)
    fs = c["counters"]["FSInvocations"]["value"]
    assert abs(c["counters"]["ShadingEfficiency"]["value"] - sp["value"] / fs) < 1e-12
    assert abs(c["counters"]["Overdraw"]["value"] - sp["value"] / (w * h)) < 1e-12
    assert fs % 16 == 0 and fs >= sp["value"]      # llvmpipe shades 4x4 blocks
    q = c["quality"]
    for k in ("RMSE", "PSNR", "SSIM", "SilhouetteError", "DepthRMSE", "CrackPixels", "NonFinitePixels"):
        assert k in q, k
    assert q["NonFinitePixels"] == 0
    for k in ("render", "heatmap"):
        p = os.path.join(run, c["images"][k])
        assert os.path.isfile(p) and os.path.getsize(p) > 0, p
assert any(f["model"] == "resolution-cost" for f in j["fits"]), j["fits"]
html = open(os.path.join(run, "report.html")).read()
for c in j["configs"]:
    assert c["key"] in html
rows = open(os.path.join(run, "results.csv")).read().strip().splitlines()
assert len(rows) == 1 + len(j["configs"]), len(rows)
print("e2e ok:", len(j["configs"]), "configs")
PY

# The report can be rebuilt from the store alone.
rm "$RUN/report.html" "$RUN/results.json"
"$BIN" report "$RUN" > /dev/null
test -s "$RUN/report.html" && test -s "$RUN/results.json"
# --budget: a pilot frame per configuration predicts its measuring time; a
# budget no configuration can meet leaves every one out, with the reason.
"$BIN" run "$SRC/tests/e2e/tiny.yaml" --out "$OUT/b" --budget 0.000001 --quiet
python3 - "$OUT/b/latest/results.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert len(j["configs"]) == 0 and len(j["left_out"]) == 4, (len(j["configs"]), len(j["left_out"]))
for l in j["left_out"]:
    assert l["reason"].startswith("over --budget"), l["reason"]
PY
echo "1 passed, 0 failed"
