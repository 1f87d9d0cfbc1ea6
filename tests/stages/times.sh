#!/usr/bin/env bash
# test_stage_times: the timed stage split (docs/counters.md, "Stage costs")
# on tests/stages/times.yaml: every counter is measured and available, the
# passes nest (GeometryTime < MinimalShadingTime < WallTime for pom, whose
# minimal-shader frame does a tenth of its instructions), and the derived
# times are the differences of their medians.  No Valgrind; ~10 s.
set -euo pipefail
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
"$BIN" run "$SRC/tests/stages/times.yaml" --out "$OUT/r" --seed 1 --quiet
python3 - "$OUT/r/latest/results.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
bad = []
for c in j["configs"]:
    t = c["params"]["technique"]
    v = {}
    for n in ("WallTime", "GeometryTime", "MinimalShadingTime", "SetupRasterTime", "FragmentTime"):
        x = c["counters"].get(n)
        if not x or "unavailable" in x:
            bad.append(f"{t}: {n} missing or unavailable: {x}")
            continue
        v[n] = x.get("median", x.get("value"))
    if len(v) < 5:
        continue
    print(t, {k: round(x / 1e6, 3) for k, x in v.items()}, "ms")
    if abs(v["SetupRasterTime"] - (v["MinimalShadingTime"] - v["GeometryTime"])) > 1e-6 * v["WallTime"]:
        bad.append(f"{t}: SetupRasterTime is not MinimalShadingTime - GeometryTime")
    if abs(v["FragmentTime"] - (v["WallTime"] - v["MinimalShadingTime"])) > 1e-6 * v["WallTime"]:
        bad.append(f"{t}: FragmentTime is not WallTime - MinimalShadingTime")
    if t == "pom" and not (0 < v["GeometryTime"] < v["MinimalShadingTime"] < v["WallTime"]):
        bad.append(f"pom: the passes do not nest: {v}")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
