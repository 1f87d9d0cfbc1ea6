#!/usr/bin/env bash
# A regression in any stage family fails the instruction gate, and only
# where it is: tests/instructions/families.yaml (normal, vertex-
# displacement, tess-displacement on the cube) counted by dmbench (the stage
# counters' run of tests/stages/techniques.yaml, STAGERUN, made once for the
# suite by test_stage_run_cube: the same configurations key for key), by
# dmbench_slowvertexshader (512 more steps per vertex in displace.vert.glsl)
# and by dmbench_slowtessshader (64 more per evaluation in tess.tes.glsl).
# `compare --counters-only` must call the slowed family's configuration a
# REGRESSION (exit 1) beyond the 0.5 % threshold, name geometry as the stage
# that grew (both slowed shaders run before rasterization), and call the
# other two PASS.
# Usage: families.sh SLOWVERTEX SLOWTESS STAGERUN  (DMBENCH_BINARY, DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
SV=${1:?usage: families.sh SLOWVERTEX SLOWTESS STAGERUN}
ST=${2:?usage: families.sh SLOWVERTEX SLOWTESS STAGERUN}
STAGERUN=${3:?usage: families.sh SLOWVERTEX SLOWTESS STAGERUN}
. "${DMBENCH_SOURCE_DIR:?}/tests/lib.sh"
SWEEP="$SRC/tests/instructions/families.yaml"
[ -f "$STAGERUN/latest/results.json" ] || { echo "no stage run in $STAGERUN (fixture test_stage_run_cube)"; exit 1; }
ln -s "$(readlink -f "$STAGERUN")" "$OUT/a"
t0=$(date +%s)
"$SV" run "$SWEEP" --out "$OUT/v" --seed 1 --quiet
"$ST" run "$SWEEP" --out "$OUT/t" --seed 1 --quiet
echo "two runs: $(( $(date +%s) - t0 )) s (load: $(cut -d' ' -f1-3 /proc/loadavg))"
for fam in v t; do
  expect_compare 1 "$OUT/a/latest" "$OUT/$fam/latest" --counters-only --json "$OUT/$fam.json"
  python3 - "$OUT/$fam.json" "$fam" <<'PY'
import json, sys
j, fam = json.load(open(sys.argv[1])), sys.argv[2]
slowed = {"v": "vertex-displacement", "t": "tess-displacement"}[fam]
assert len(j["configs"]) == 3, j["configs"]
for c in j["configs"]:
    ratio = c.get("instructions_ratio")
    if slowed in c["configuration"]:
        assert c["verdict"] == "REGRESSION" and ratio > 1.005, c
        assert "; by stage: geometry x" in c["note"] and c["note"].endswith("; geometry grew most"), c["note"]
    else:
        assert c["verdict"] == "PASS", c
    print(f"slower {slowed} stage: {c['configuration']}: {c['verdict']}, instructions x{ratio:.4f}"
          f"{'; ' + c['note'].split('; ', 1)[1] if c['verdict'] != 'PASS' else ''}")
PY
done
