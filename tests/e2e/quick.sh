#!/usr/bin/env bash
# The embedded default sweep in its --quick form (README, the 1-minute
# version): no file, every technique, results and report written, nothing
# failed; every configuration's FLIP in [0, 1] with its map, and the same
# to 1e-6 in a second run.  Prints its wall time; the time bound only
# catches a run-away.  The runs are the suite's (tests/e2e/quick_runs.sh:
# a, with progress, and b, the same seed).
set -euo pipefail
BIN=${DMBENCH_BINARY:?}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
RUNS=$(bash "${DMBENCH_SOURCE_DIR:?}/tests/e2e/quick_runs.sh" --use "$OUT/runs")
took=$(cat "$RUNS/a.seconds")
tail -1 "$RUNS/a.log"
python3 - "$RUNS/a/latest/results.json" "$BIN" <<'PY'
import json, subprocess, sys
j = json.load(open(sys.argv[1]))
techs = [l.split()[0] for l in subprocess.run([sys.argv[2], "list", "techniques"], capture_output=True,
         text=True, check=True).stdout.splitlines() if l and not l.startswith(" ")]
ran = {c["params"]["technique"] for c in j["configs"]}
missing = set(techs) - ran - {"reference-mesh"}
assert not missing, missing
bad = [(c["params"]["technique"], c["reason"]) for c in j["configs"] if c["status"] != "ok"]
assert not bad, bad
assert j["run"]["sweep"] == "quick"
print("quick:", len(j["configs"]), "configurations, every technique")
PY
echo "quick sweep: ${took} s"
[ "$took" -lt 300 ]
python3 - "$(readlink -f "$RUNS/a/latest")" "$(readlink -f "$RUNS/b/latest")" <<'PY'
import json, os, sys
runs = [json.load(open(os.path.join(d, "results.json"))) for d in sys.argv[1:]]
flip = [{c["key"]: c["quality"]["FLIP"] for c in r["configs"] if c.get("quality")} for r in runs]
for c in runs[0]["configs"]:
    q = c.get("quality")
    if not q:
        continue
    assert 0 <= q["FLIPQ1"] <= q["FLIPMedian"] <= q["FLIPQ3"] <= q["FLIPMax"] <= 1, (c["key"], q)
    assert 0 < q["FLIP"] <= q["FLIPMax"] and q["FLIPPixelsPerDegree"] == 67.0206, (c["key"], q)
    assert os.path.isfile(os.path.join(sys.argv[1], c["images"]["flip"])), c["images"]
assert flip[0].keys() == flip[1].keys() and flip[0]
worst = max(abs(flip[0][k] - flip[1][k]) for k in flip[0])
assert worst <= 1e-6, worst
print("FLIP:", len(flip[0]), "configurations, largest difference between two runs", worst)
PY
echo "1 passed, 0 failed"
