#!/usr/bin/env bash
# test_stage_instructions: the stage counters of the Instructions pass
# (docs/counters.md, "Stage costs") on tests/stages/fullscreen.yaml and on
# the cube, tests/stages/techniques.yaml and tests/stages/reference.yaml
# (reference-mesh, in a run of its own: it takes as long to count as the
# nine others), each run once for the suite by test_stage_run_fullscreen,
# test_stage_run_cube and test_stage_run_reference (FULL and CUBE..., their
# output roots; the cube's nine are also test_instructions_families').
#  - every technique: geometry, raster and fragment are positive, they add
#    up to Instructions within 1 %, and the residual (geometry work the
#    minimal fragment shader changed, which does not enter the parts) is
#    below 0.2 % of the frame (2 % for unlit texture, explained in the doc);
#  - by hand: phong and texture on the full-screen quad at 64x64, 128x128
#    and 256x256 cover exactly 4096, 16384 and 65536 pixels
#    (SamplesPassed), the geometry is the same at every size within 0.5 %
#    of the frame,
#    and fragment instructions are F0 + f x pixels: the cost per added
#    pixel is equal between the sizes within 2 % and F0 (per-draw state of
#    the fragment stage) is under 5 % of the 64x64 fragment count.
# Usage: stages.sh FULL CUBE...  (DMBENCH_SOURCE_DIR set by ctest)
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: stages.sh FULL CUBE..."; exit 2; }
runs=()
for d in "$@"; do
  [ -f "$d/latest/results.json" ] || { echo "no stage run in $d (fixtures test_stage_run_*)"; exit 1; }
  runs+=("$d/latest/results.json")
done
python3 - "${runs[@]}" <<'PY'
import json, sys
j = {"configs": [c for p in sys.argv[1:] for c in json.load(open(p))["configs"]]}
# a technique counted twice (in two of the runs) would hide a missing one
keys = [c["key"] for c in j["configs"]]
assert len(keys) == len(set(keys)), "a configuration is in two of the runs"
fails = []
def val(c, n):
    x = c["counters"].get(n)
    assert x is not None, (c["label"], n, "missing")
    assert "unavailable" not in x, (c["label"], n, x["unavailable"])
    return x["median"] if "median" in x else x["value"]
full, I64 = {}, {}
techs = set()
for c in j["configs"]:
    assert c["status"] == "ok", (c["label"], c.get("reason"))
    p = c["params"]
    I, g, r, f, res = (val(c, n) for n in ("Instructions", "GeometryInstructions", "RasterInstructions",
                                           "FragmentInstructions", "StageResidual"))
    print(f"{p['technique']:20s} {p['mesh']:10s} {p.get('resolution','')}: I {I:.0f} = geometry {g:.0f} "
          f"+ raster {r:.0f} + fragment {f:.0f}; residual {res:.0f} ({100*res/I:.3f} %)")
    if not (g > 0 and r > 0 and f > 0):
        fails.append(f"{c['label']}: a stage is not positive")
    if abs(g + r + f - I) > 0.01 * I:
        fails.append(f"{c['label']}: parts add to {g+r+f:.0f}, Instructions {I:.0f}")
    # the residual (geometry work the minimal shader changed) does not enter
    # the parts; it is explained for unlit texture (docs/counters.md): its
    # shader reads only the UV, the minimal one every input its interface
    # declares.  Elsewhere it is under 0.2 % of the frame.
    if abs(res) > (0.02 if p["technique"] == "texture" else 0.002) * I:
        fails.append(f"{c['label']}: residual {res:.0f} is too large against {I:.0f}")
    if p["mesh"] == "cube":
        techs.add(p["technique"])
    else:
        full[(p["technique"], p["resolution"])] = (val(c, "SamplesPassed"), g, f)
        if p["resolution"] == "64x64":
            I64[p["technique"]] = I
assert len(techs) == 10, techs
for t in ("phong", "texture"):
    pts = [full[(t, r)] for r in ("64x64", "128x128", "256x256")]
    (s1, g1, f1), (s2, g2, f2), (s3, g3, f3) = pts
    print(f"{t} full-screen: pixels {s1:.0f} / {s2:.0f} / {s3:.0f}, geometry {g1:.0f} / {g2:.0f} / {g3:.0f}, "
          f"fragment {f1:.0f} / {f2:.0f} / {f3:.0f} (x{f2/f1:.4f}, x{f3/f1:.4f})")
    if (s1, s2, s3) != (4096, 16384, 65536):
        fails.append(f"{t}: covered pixels {s1}, {s2}, {s3}, expected 4096, 16384, 65536")
    # the discard window still walks the empty scene's bins (~140 instructions
    # per 64x64 tile): under 0.5 % of the smallest frame
    if max(g1, g2, g3) - min(g1, g2, g3) > 0.005 * I64[t]:
        fails.append(f"{t}: geometry changed with the resolution: {g1}, {g2}, {g3}")
    # fragment = F0 + f*pixels: the cost per added pixel is the same between
    # every pair of resolutions within 2 % (llvmpipe skips a branch for a
    # whole 4x4 block where no pixel takes it, so shading is not exactly
    # data-independent: 1.0 % measured for phong and texture), F0 is below
    # 5 % of the smallest frame's
    d12, d23 = (f2 - f1) / (s2 - s1), (f3 - f2) / (s3 - s2)
    f0 = f1 - d12 * s1
    print(f"{t}: fragment per added pixel {d12:.2f} and {d23:.2f}; fixed part {f0:.0f}")
    if abs(d23 / d12 - 1) > 0.02:
        fails.append(f"{t}: fragment per pixel {d12:.2f} then {d23:.2f}, not linear within 2 %")
    if abs(f0) > 0.05 * f1:
        fails.append(f"{t}: fragment's fixed part {f0:.0f} is over 5 % of {f1:.0f}")
for m in fails:
    print("FAIL:", m)
sys.exit(1 if fails else 0)
PY
